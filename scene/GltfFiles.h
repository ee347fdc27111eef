#pragma once
#include <tiny_gltf.h>

#include <string>

namespace baker {

// A scene may read files beside it or below its folder, nothing else: no absolute paths, no
// "..", no other URI schemes (data: URIs are fine). Checks every buffers[i].uri and
// images[i].uri of the .gltf or .glb at `path` before anything is loaded and throws InputError
// naming the file, the glTF path and the URI. A file tinygltf cannot parse is left for its own
// error message.
void checkExternalUris(const std::string& path);

// File access for tinygltf confined to the scene's folder: no `~` or `$VAR` expansion of URIs,
// and no fallback to the current directory (tinygltf tries "./NAME" when the scene's folder has
// no NAME). `sceneFolder` must outlive the loader.
tinygltf::FsCallbacks confinedFileSystem(const std::string& sceneFolder);

// The folder tinygltf resolves `path`'s URIs against (as tinygltf computes it).
std::string sceneFolderOf(const std::string& path);

}  // namespace baker
