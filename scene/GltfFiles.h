#pragma once
#include <tiny_gltf.h>

#include <nlohmann/json.hpp>
#include <string>

namespace baker {

// The JSON of the .gltf, or the JSON chunk of the .glb, at `path`; a discarded value when it
// cannot be parsed (tinygltf's own error message then explains why).
nlohmann::json readGltfJson(const std::string& path);

// A scene may read files beside it or below its folder, nothing else: no absolute paths, no
// "..", no other URI schemes (data: URIs are fine). Checks every buffers[i].uri and
// images[i].uri of the scene's JSON `root` before anything is loaded and throws InputError
// naming the file `path`, the glTF path and the URI.
void checkExternalUris(const nlohmann::json& root, const std::string& path);

// File access for tinygltf confined to the scene's folder: no `~` or `$VAR` expansion of URIs,
// and no fallback to the current directory (tinygltf tries "./NAME" when the scene's folder has
// no NAME). `sceneFolder` must outlive the loader.
tinygltf::FsCallbacks confinedFileSystem(const std::string& sceneFolder);

// A relative URI as a file name: %XX escapes decoded (others left as they are).
std::string percentDecoded(const std::string& uri);

// The folder tinygltf resolves `path`'s URIs against (as tinygltf computes it).
std::string sceneFolderOf(const std::string& path);

}  // namespace baker
