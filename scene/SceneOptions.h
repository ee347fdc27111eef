#pragma once
#include <string>
#include <vector>

#include "scene/Environment.h"

namespace baker {

// What a bake adds to a glTF file to describe the scene it sees: which glTF scene, and the
// environment (glTF has none). Errors name these fields as "scene", "env_intensity",
// "env_rotation" and "sky" (a map that cannot be read is an InputError naming its file).
struct SceneOptions {
  int scene = -1;                   // the glTF scene index; -1: the file's default scene
  std::string environmentMap;       // a lat-long HDR/EXR
  double environmentIntensity = 1;  // multiplies the map
  double environmentRotation = 0;   // degrees about +Y, right-handed
  std::string sky;                  // "r,g,b", a constant radiance instead of a map
};

// The environment the options describe (none when they name none). Reads the map through
// OpenImageIO and builds its sampling tables once. SettingError naming the field, or InputError naming the file, when a
// value is malformed; negative or non-finite texels become 0 with a warning.
Environment environmentFromOptions(const SceneOptions& options, std::vector<std::string>& warnings);

}  // namespace baker
