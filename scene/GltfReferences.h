#pragma once
#include <nlohmann/json.hpp>
#include <string>

namespace baker {

// tinygltf rejects some files itself, before our loader sees the model, with messages that
// name no glTF path ("primitive indices accessor out of bounds", "Spot light description not
// found.", "'count' property is missing in Accessor."), and accepts others silently (a
// 3-number baseColorFactor is dropped, a 15-number matrix read as identity): dangling index
// accessors, typed lights and cameras without their object, missing required properties,
// wrong-length number arrays, a data: URI shorter than its byteLength, asset.version other
// than 2.x. This finds those cases in the scene's JSON `root` first and throws InputError naming
// the file `path` and the glTF path. Everything else is left to tinygltf and
// the loader, which check it with paths of their own.
void checkReferencesTinygltfRejects(const nlohmann::json& root, const std::string& path);

}  // namespace baker
