#include "scene/GltfReferences.h"

#include <fmt/format.h>

#include <cstdint>
#include <utility>
#include <vector>

#include "common/Error.h"

namespace baker {
namespace {

std::size_t arraySize(const nlohmann::json& root, const char* key) {
  auto it = root.find(key);
  return it != root.end() && it->is_array() ? it->size() : 0;
}

// Index-valued fields tinygltf resolves while parsing: -1 when absent or not an integer.
long long indexField(const nlohmann::json& object, const char* key) {
  auto it = object.find(key);
  return it != object.end() && it->is_number_integer() ? it->get<long long>() : -1;
}

void checkPrimitiveIndices(const nlohmann::json& root, const std::string& path) {
  auto meshes = root.find("meshes");
  if (meshes == root.end() || !meshes->is_array()) return;
  const std::size_t accessorCount = arraySize(root, "accessors"), viewCount = arraySize(root, "bufferViews");
  for (std::size_t m = 0; m < meshes->size(); ++m) {
    const nlohmann::json& mesh = (*meshes)[m];
    auto primitives = mesh.is_object() ? mesh.find("primitives") : mesh.end();
    if (!mesh.is_object() || primitives == mesh.end() || !primitives->is_array()) continue;
    for (std::size_t p = 0; p < primitives->size(); ++p) {
      const nlohmann::json& primitive = (*primitives)[p];
      if (!primitive.is_object() || !primitive.contains("indices")) continue;
      const long long accessor = indexField(primitive, "indices");
      const std::string where = fmt::format("meshes[{}].primitives[{}].indices", m, p);
      if (accessor < 0 || std::size_t(accessor) >= accessorCount)
        throw InputError(fmt::format("{}: {} refers to accessor {}, which does not exist ({} accessors)", path, where,
                                     primitive["indices"].dump(), accessorCount));
      // Index accessors need a bufferView in tinygltf (sparse-only indices are refused there).
      const long long view = indexField(root["accessors"][accessor], "bufferView");
      if (view < 0 || std::size_t(view) >= viewCount)
        throw InputError(fmt::format("{}: accessors[{}].bufferView (the {}) must name one of the {} bufferViews",
                                     path, accessor, where, viewCount));
    }
  }
}

// A light or camera of some type needs the object of that name beside it.
void checkTypedObjects(const nlohmann::json& list, const std::string& listPath, const std::string& path,
                       std::initializer_list<const char*> typesWithObject) {
  if (!list.is_array()) return;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const nlohmann::json& item = list[i];
    if (!item.is_object() || !item.contains("type") || !item["type"].is_string()) continue;
    const std::string type = item["type"];
    for (const char* needed : typesWithObject)
      if (type == needed && (!item.contains(needed) || !item[needed].is_object()))
        throw InputError(fmt::format("{}: {}[{}] has type \"{}\" but no \"{}\" object", path, listPath, i, type,
                                     needed));
  }
}

// Properties the glTF schema requires, which tinygltf reports only by object kind
// ("'count' property is missing in Accessor.").
void checkRequiredProperties(const nlohmann::json& root, const std::string& path) {
  static const std::vector<std::pair<const char*, std::vector<const char*>>> kRequired = {
      {"accessors", {"componentType", "count", "type"}},
      {"bufferViews", {"buffer", "byteLength"}},
      {"buffers", {"byteLength"}},
      {"meshes", {"primitives"}},
      {"skins", {"joints"}},
      {"animations", {"channels", "samplers"}},
      {"cameras", {"type"}},
  };
  for (const auto& [key, properties] : kRequired) {
    auto list = root.find(key);
    if (list == root.end() || !list->is_array()) continue;
    for (std::size_t i = 0; i < list->size(); ++i)
      for (const char* property : properties)
        if (!(*list)[i].is_object() || !(*list)[i].contains(property))
          throw InputError(fmt::format("{}: {}[{}].{} is required and missing", path, key, i, property));
  }
  auto meshes = root.find("meshes");
  if (meshes == root.end() || !meshes->is_array()) return;
  for (std::size_t m = 0; m < meshes->size(); ++m) {
    const nlohmann::json& primitives = (*meshes)[m]["primitives"];
    if (!primitives.is_array()) continue;
    for (std::size_t p = 0; p < primitives.size(); ++p)
      if (!primitives[p].is_object() || !primitives[p].contains("attributes"))
        throw InputError(fmt::format("{}: meshes[{}].primitives[{}].attributes is required and missing", path, m, p));
  }
}

// Fixed-length number arrays: tinygltf drops a wrong-length baseColorFactor and reads a short
// matrix as identity, silently.
void checkFixedLengthArrays(const nlohmann::json& root, const std::string& path) {
  auto require = [&](const nlohmann::json& object, const char* key, std::size_t length, const std::string& where) {
    if (!object.is_object() || !object.contains(key)) return;
    const nlohmann::json& value = object[key];
    bool ok = value.is_array() && value.size() == length;
    for (std::size_t i = 0; ok && i < length; ++i) ok = value[i].is_number();
    if (!ok) throw InputError(fmt::format("{}: {}.{} must be an array of {} numbers", path, where, key, length));
  };
  if (root.contains("nodes") && root["nodes"].is_array())
    for (std::size_t i = 0; i < root["nodes"].size(); ++i) {
      const std::string where = fmt::format("nodes[{}]", i);
      require(root["nodes"][i], "matrix", 16, where);
      require(root["nodes"][i], "translation", 3, where);
      require(root["nodes"][i], "rotation", 4, where);
      require(root["nodes"][i], "scale", 3, where);
    }
  if (root.contains("materials") && root["materials"].is_array())
    for (std::size_t i = 0; i < root["materials"].size(); ++i) {
      const nlohmann::json& material = root["materials"][i];
      require(material, "emissiveFactor", 3, fmt::format("materials[{}]", i));
      if (material.is_object() && material.contains("pbrMetallicRoughness"))
        require(material["pbrMetallicRoughness"], "baseColorFactor", 4,
                fmt::format("materials[{}].pbrMetallicRoughness", i));
    }
}

// tinygltf requires a data: URI to hold exactly byteLength bytes and reports a mismatch with
// the whole URI in its message and no buffer index.
void checkDataUriLengths(const nlohmann::json& root, const std::string& path) {
  if (!root.contains("buffers") || !root["buffers"].is_array()) return;
  for (std::size_t i = 0; i < root["buffers"].size(); ++i) {
    const nlohmann::json& buffer = root["buffers"][i];
    if (!buffer.is_object() || !buffer.contains("uri") || !buffer["uri"].is_string()) continue;
    if (!buffer.contains("byteLength") || !buffer["byteLength"].is_number_unsigned()) continue;
    const std::string& uri = buffer["uri"].get_ref<const std::string&>();
    const std::size_t comma = uri.find(',');
    if (uri.rfind("data:", 0) != 0 || comma == std::string::npos || uri.find(";base64,") != comma - 7) continue;
    std::size_t encoded = uri.size() - comma - 1;
    std::size_t padding = 0;
    while (padding < 2 && encoded > padding && uri[uri.size() - 1 - padding] == '=') ++padding;
    const std::size_t decoded = encoded / 4 * 3 - padding;
    const std::uint64_t declared = buffer["byteLength"].get<std::uint64_t>();
    if (declared != decoded)
      throw InputError(fmt::format("{}: buffers[{}].byteLength is {}, but its data: URI holds {} bytes", path, i,
                                   declared, decoded));
  }
}

}  // namespace

void checkReferencesTinygltfRejects(const nlohmann::json& root, const std::string& path) {
  if (root.is_discarded() || !root.is_object()) return;
  if (root.contains("asset") && root["asset"].is_object() && root["asset"].contains("version")) {
    const nlohmann::json& version = root["asset"]["version"];
    if (!version.is_string() || version.get<std::string>().rfind("2.", 0) != 0)
      throw InputError(fmt::format("{}: asset.version is {}; only glTF 2.x is read", path, version.dump()));
  }
  checkRequiredProperties(root, path);
  checkFixedLengthArrays(root, path);
  checkDataUriLengths(root, path);
  checkPrimitiveIndices(root, path);
  if (root.contains("cameras"))
    checkTypedObjects(root["cameras"], "cameras", path, {"perspective", "orthographic"});
  auto extensions = root.find("extensions");
  if (extensions != root.end() && extensions->is_object() && extensions->contains("KHR_lights_punctual")) {
    const nlohmann::json& lights = (*extensions)["KHR_lights_punctual"];
    if (lights.is_object() && lights.contains("lights"))
      checkTypedObjects(lights["lights"], "extensions.KHR_lights_punctual.lights", path, {"spot"});
  }
}

}  // namespace baker
