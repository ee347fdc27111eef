#pragma once
#include <string>

namespace baker {

// Copies a glTF scene into `directory` so that a page can load it from there: a .glb as it is; a
// .gltf with every file its buffers and images refer to (data: URIs stay inside it), renamed
// buffer_N.ext and image_N.ext and the copy's URIs rewritten to match, so that no reference
// leaves the directory. Returns the scene's URL relative to the directory's parent
// ("scene/NAME"). InputError naming the glTF and its field for a file that is not there.
std::string copyScene(const std::string& scenePath, const std::string& directory);

}  // namespace baker
