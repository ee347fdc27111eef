#pragma once
#include <string>

#include "scene/Scene.h"

namespace baker {

// Loads a .gltf or .glb file into a flat world-space Scene. Throws InputError with the
// file and glTF path of the first problem found.
Scene loadGltf(const std::string& path);

}  // namespace baker
