#pragma once
#include <string>

#include "scene/Scene.h"
#include "scene/SceneOptions.h"

namespace baker {

// Loads a .gltf or .glb file and the environment `options` describe into a Scene: the glTF
// scene `options.scene` (default: the file's default scene), each mesh read once and placed by
// every node that uses it, materials with their textures decoded, KHR_lights_punctual lights.
// Throws InputError with the file and glTF path of the first problem a user must fix; what a
// user would step over is in Scene::warnings.
Scene loadGltf(const std::string& path, const SceneOptions& options = {});

}  // namespace baker
