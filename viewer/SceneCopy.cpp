#include "viewer/SceneCopy.h"

#include <fmt/format.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "common/Error.h"
#include "scene/GltfFiles.h"

namespace baker {
namespace {

void copyFile(const std::filesystem::path& from, const std::filesystem::path& to, const std::string& where) {
  std::error_code ec;
  std::filesystem::create_directories(to.parent_path(), ec);
  std::filesystem::copy_file(from, to, std::filesystem::copy_options::overwrite_existing, ec);
  if (ec) throw InputError(fmt::format("{}: cannot copy {}: {}", where, from.string(), ec.message()));
}

}  // namespace

std::string copyScene(const std::string& scenePath, const std::string& directory) {
  const nlohmann::json gltf = readGltfJson(scenePath);
  if (gltf.is_discarded() || !gltf.is_object())
    throw InputError(fmt::format("{}: not a glTF file this tool can read (its JSON does not parse)", scenePath));
  checkExternalUris(gltf, scenePath);
  const std::filesystem::path scene(scenePath), to(directory);
  copyFile(scene, to / scene.filename(), scenePath);
  for (const char* array : {"buffers", "images"}) {
    const auto entries = gltf.find(array);
    if (entries == gltf.end() || !entries->is_array()) continue;
    for (const nlohmann::json& entry : *entries) {
      if (!entry.is_object() || !entry.contains("uri") || !entry["uri"].is_string()) continue;
      const std::string uri = entry["uri"].get<std::string>();
      if (uri.rfind("data:", 0) == 0) continue;
      const std::filesystem::path relative = std::filesystem::path(percentDecoded(uri)).lexically_normal();
      std::error_code ec;
      if (std::filesystem::is_regular_file(scene.parent_path() / relative, ec))
        copyFile(scene.parent_path() / relative, to / relative, scenePath);
    }
  }
  return "scene/" + scene.filename().string();
}

}  // namespace baker
