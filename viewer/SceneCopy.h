#pragma once
#include <string>

namespace baker {

// Copies a glTF scene (.gltf or .glb) into `directory` so that a page can load it from there,
// with every file its buffers and images refer to at the same relative path. Scenes may refer
// only to files in their folder or below (checkExternalUris, as the bake loads them), so nothing
// from elsewhere is copied; an image that is missing stays missing, as it is for the bake.
// Returns the scene's URL relative to the directory's parent ("scene/NAME"). InputError naming
// the glTF and its field for a reference it refuses or a buffer that is not there.
std::string copyScene(const std::string& scenePath, const std::string& directory);

}  // namespace baker
