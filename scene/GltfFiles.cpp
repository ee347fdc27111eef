#include "scene/GltfFiles.h"

#include <fmt/format.h>

#include <cctype>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>

#include "common/Error.h"

namespace baker {
namespace {

// The JSON text of a .gltf, or the JSON chunk of a .glb; "" when neither can be found (then
// tinygltf reports the problem).
std::string jsonText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  char header[20];
  if (!in.read(header, sizeof header)) {
    in.clear();
    in.seekg(0);
    return std::string(std::istreambuf_iterator<char>(in), {});
  }
  std::uint32_t magic, chunkLength, chunkType;
  std::memcpy(&magic, header, 4);
  std::memcpy(&chunkLength, header + 12, 4);
  std::memcpy(&chunkType, header + 16, 4);
  if (magic != 0x46546C67u) {  // "glTF": not a binary container
    in.seekg(0);
    return std::string(std::istreambuf_iterator<char>(in), {});
  }
  if (chunkType != 0x4E4F534Au) return "";  // "JSON" must come first
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  if (ec || chunkLength > size - sizeof header) return "";
  std::string text(chunkLength, '\0');
  if (!in.read(text.data(), chunkLength)) return "";
  return text;
}


// Why `uri` may not be read, or "" when it may: a relative path that stays in the folder.
std::string refusal(const std::string& uri) {
  if (uri.rfind("data:", 0) == 0) return "";
  const std::string path = percentDecoded(uri);
  std::size_t schemeEnd = 0;
  while (schemeEnd < path.size() && (std::isalnum((unsigned char)path[schemeEnd]) || path[schemeEnd] == '+' ||
                                     path[schemeEnd] == '-' || path[schemeEnd] == '.'))
    ++schemeEnd;
  if (schemeEnd > 0 && schemeEnd < path.size() && path[schemeEnd] == ':' && std::isalpha((unsigned char)path[0]))
    return "is not a relative file name or a data: URI";
  if (!path.empty() && (path[0] == '/' || path[0] == '\\')) return "is an absolute path outside the scene's folder";
  // Lexically: every ".." must stay below the folder at every step, so "a/../b" is fine and
  // "a/../../b" is not.
  int depth = 0;
  std::size_t start = 0;
  while (start <= path.size()) {
    const std::size_t end = std::min(path.find_first_of("/\\", start), path.size());
    const std::string part = path.substr(start, end - start);
    if (part == "..") {
      if (--depth < 0) return "leaves the scene's folder";
    } else if (!part.empty() && part != ".") {
      ++depth;
    }
    start = end + 1;
  }
  return "";
}

void checkArray(const nlohmann::json& root, const char* key, const std::string& path) {
  const auto array = root.find(key);
  if (array == root.end() || !array->is_array()) return;
  for (std::size_t i = 0; i < array->size(); ++i) {
    const nlohmann::json& item = (*array)[i];
    if (!item.is_object()) continue;
    const auto uri = item.find("uri");
    if (uri == item.end() || !uri->is_string()) continue;
    const std::string why = refusal(uri->get<std::string>());
    if (!why.empty())
      throw InputError(fmt::format("{}: {}[{}].uri \"{}\" {}; only files in the scene's folder or below are read",
                                   path, key, i, uri->get<std::string>(), why));
    // A missing buffer stops the load (a missing image only loses its texture: a warning later).
    if (std::string(key) == "buffers" && uri->get<std::string>().rfind("data:", 0) != 0) {
      const std::filesystem::path file =
          std::filesystem::path(path).parent_path() / percentDecoded(uri->get<std::string>());
      std::error_code ec;
      if (!std::filesystem::is_regular_file(file, ec))
        throw InputError(fmt::format("{}: {}[{}].uri \"{}\": no such file beside the scene", path, key, i,
                                     uri->get<std::string>()));
    }
  }
}

bool confinedFileExists(const std::string& candidate, void* user) {
  const std::string& folder = *static_cast<const std::string*>(user);
  if (!folder.empty()) {
    const std::string prefix = folder.back() == '/' ? folder : folder + "/";
    if (candidate.compare(0, prefix.size(), prefix) != 0) return false;
  }
  std::error_code ec;
  return std::filesystem::is_regular_file(candidate, ec);
}

std::string unexpanded(const std::string& path, void*) { return path; }

}  // namespace

nlohmann::json readGltfJson(const std::string& path) {
  // tinygltf converts JSON recursively and overflows the stack on deep nesting (a few hundred
  // kilobytes of brackets suffice); glTF itself never needs more than a few levels.
  constexpr int kMaxDepth = 256;
  auto limitDepth = [&](int depth, nlohmann::json::parse_event_t, nlohmann::json&) {
    if (depth > kMaxDepth)
      throw InputError(fmt::format("{}: JSON nests deeper than {} levels; refusing to load it", path, kMaxDepth));
    return true;
  };
  return nlohmann::json::parse(jsonText(path), limitDepth, false);
}

void checkExternalUris(const nlohmann::json& root, const std::string& path) {
  if (root.is_discarded() || !root.is_object()) return;
  checkArray(root, "buffers", path);
  checkArray(root, "images", path);
}

tinygltf::FsCallbacks confinedFileSystem(const std::string& sceneFolder) {
  tinygltf::FsCallbacks fs{};
  fs.FileExists = confinedFileExists;
  fs.ExpandFilePath = unexpanded;
  fs.ReadWholeFile = tinygltf::ReadWholeFile;
  fs.WriteWholeFile = tinygltf::WriteWholeFile;
  fs.user_data = const_cast<std::string*>(&sceneFolder);
  return fs;
}

std::string percentDecoded(const std::string& uri) {
  std::string out;
  for (std::size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] == '%' && i + 2 < uri.size() && std::isxdigit((unsigned char)uri[i + 1]) &&
        std::isxdigit((unsigned char)uri[i + 2])) {
      out += char(std::stoi(uri.substr(i + 1, 2), nullptr, 16));
      i += 2;
    } else {
      out += uri[i];
    }
  }
  return out;
}

std::string sceneFolderOf(const std::string& path) {
  const std::size_t slash = path.find_last_of("/\\");
  return slash == std::string::npos ? "" : path.substr(0, slash);
}

}  // namespace baker
