#pragma once
#include <CLI/CLI.hpp>

#include <string>
#include <vector>

#include "scene/Environment.h"

namespace baker {

// What the command line adds to a glTF file to describe the scene a bake sees: which glTF
// scene, and the environment (glTF has none). Shared by every command that loads a scene.
struct SceneOptions {
  int scene = -1;                   // --scene: the glTF scene index; -1: the file's default scene
  std::string environmentMap;       // --env: a lat-long HDR/EXR
  double environmentIntensity = 1;  // --env-intensity: multiplies the map
  double environmentRotation = 0;   // --env-rotation: degrees about +Y, right-handed
  std::string sky;                  // --sky: "r,g,b", a constant radiance instead of a map
};

// Registers --scene, --env, --env-intensity, --env-rotation and --sky on `app`.
void addSceneOptions(CLI::App& app, SceneOptions& options);

// The environment the options describe (none when they name none). Reads the map through
// OpenImageIO and builds its sampling tables once. InputError naming the flag or file when a
// value is malformed; negative or non-finite texels become 0 with a warning.
Environment environmentFromOptions(const SceneOptions& options, std::vector<std::string>& warnings);

}  // namespace baker
