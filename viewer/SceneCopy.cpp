#include "viewer/SceneCopy.h"

#include <fmt/format.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "common/Error.h"

namespace baker {
namespace {

// A relative URI as a path: %XX escapes decoded.
std::string decodeUri(const std::string& uri, const std::string& where) {
  std::string out;
  for (std::size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] != '%') {
      out += uri[i];
      continue;
    }
    if (i + 2 >= uri.size() || !std::isxdigit(uint8_t(uri[i + 1])) || !std::isxdigit(uint8_t(uri[i + 2])))
      throw InputError(fmt::format("{}: \"{}\" has a malformed %-escape", where, uri));
    out += char(std::stoi(uri.substr(i + 1, 2), nullptr, 16));
    i += 2;
  }
  return out;
}

// Copies the files of one array's URIs (buffers or images) and points the copy at them.
void copyReferences(nlohmann::json& gltf, const char* array, const char* prefix, const std::filesystem::path& from,
                    const std::filesystem::path& to, const std::string& scenePath) {
  if (!gltf.contains(array) || !gltf[array].is_array()) return;
  nlohmann::json& entries = gltf[array];
  for (std::size_t i = 0; i < entries.size(); ++i) {
    if (!entries[i].is_object() || !entries[i].contains("uri") || !entries[i]["uri"].is_string()) continue;
    const std::string uri = entries[i]["uri"].get<std::string>();
    if (uri.rfind("data:", 0) == 0) continue;
    const std::string where = fmt::format("{}: {}[{}].uri", scenePath, array, i);
    const std::filesystem::path source = from / decodeUri(uri, where);
    std::error_code ec;
    if (!std::filesystem::is_regular_file(source, ec))
      throw InputError(fmt::format("{} \"{}\": no such file", where, uri));
    const std::string name = fmt::format("{}_{}{}", prefix, i, source.extension().string());
    std::filesystem::copy_file(source, to / name, std::filesystem::copy_options::overwrite_existing, ec);
    if (ec) throw InputError(fmt::format("{} \"{}\": cannot copy: {}", where, uri, ec.message()));
    entries[i]["uri"] = name;
  }
}

}  // namespace

std::string copyScene(const std::string& scenePath, const std::string& directory) {
  const std::filesystem::path scene(scenePath), to(directory);
  std::filesystem::create_directories(to);
  const std::string name = scene.filename().string();
  if (scene.extension() != ".gltf") {
    std::error_code ec;
    std::filesystem::copy_file(scene, to / name, ec);
    if (ec) throw InputError(fmt::format("{}: cannot copy the scene: {}", scenePath, ec.message()));
    return "scene/" + name;
  }
  std::ifstream in(scenePath);
  nlohmann::json gltf;
  try {
    gltf = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(fmt::format("{}: not valid JSON: {}", scenePath, oneLine(e.what())));
  }
  copyReferences(gltf, "buffers", "buffer", scene.parent_path(), to, scenePath);
  copyReferences(gltf, "images", "image", scene.parent_path(), to, scenePath);
  std::ofstream(to / name) << gltf.dump() << "\n";
  return "scene/" + name;
}

}  // namespace baker
