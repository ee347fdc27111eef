#include "scene/GltfReferences.h"

#include <fmt/format.h>

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

}  // namespace

void checkReferencesTinygltfRejects(const nlohmann::json& root, const std::string& path) {
  if (root.is_discarded() || !root.is_object()) return;
  checkRequiredProperties(root, path);
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
