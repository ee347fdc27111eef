#include "scene/GltfMaterials.h"

#include <fmt/format.h>

#include <cmath>
#include <map>

#include "common/Error.h"

namespace baker {
namespace {

// glTF names TEXCOORD_n sets; real assets use a handful, engines at most eight.
constexpr int kMaxTexcoordSets = 32;

Wrap wrapMode(int value, const std::string& where) {
  switch (value) {
    case TINYGLTF_TEXTURE_WRAP_REPEAT: return Wrap::Repeat;
    case TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE: return Wrap::ClampToEdge;
    case TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT: return Wrap::MirroredRepeat;
  }
  throw InputError(fmt::format("{} {} is not REPEAT (10497), CLAMP_TO_EDGE (33071) or MIRRORED_REPEAT (33648)", where,
                               value));
}

class MaterialReader {
 public:
  MaterialReader(const tinygltf::Model& model, const GltfImages& images, const std::string& file,
                 std::vector<std::string>& warnings)
      : model_(model), images_(images), file_(file), warnings_(warnings) {}

  GltfMaterials read() {
    for (std::size_t i = 0; i < model_.materials.size(); ++i) out_.materials.push_back(readMaterial(int(i)));
    // Primitives without a material get glTF's default: white, not emissive, opaque, single-sided.
    out_.defaultMaterial = std::uint32_t(out_.materials.size());
    Material fallback;
    fallback.name = "(default)";
    out_.materials.push_back(fallback);
    if (clampedBaseColors_ > 0)
      warnings_.push_back(fmt::format("{}: {} material(s) have a baseColorFactor above 1 (first: {}); clamped to 1 so "
                                      "that surfaces do not reflect more light than they receive",
                                      file_, clampedBaseColors_, firstClamped_));
    return std::move(out_);
  }

 private:
  [[noreturn]] void fail(const std::string& path, const std::string& what) const {
    throw InputError(fmt::format("{}: {} {}", file_, path, what));
  }

  // `values` must hold `count` finite, non-negative numbers.
  void requireColor(const std::vector<double>& values, std::size_t count, const std::string& path) const {
    if (values.size() != count) fail(path, fmt::format("must have {} numbers, has {}", count, values.size()));
    for (double v : values)
      if (!std::isfinite(v) || v < 0.0) fail(path, "must be finite and non-negative");
  }

  double number(const tinygltf::Value& object, const char* key, double fallback, const std::string& path) const {
    if (!object.Has(key)) return fallback;
    const tinygltf::Value& v = object.Get(key);
    if (!v.IsNumber() || !std::isfinite(v.GetNumberAsDouble())) fail(path + "." + key, "must be a finite number");
    return v.GetNumberAsDouble();
  }

  Material readMaterial(int index) {
    const tinygltf::Material& src = model_.materials[index];
    const std::string path = fmt::format("materials[{}]", index);
    Material m;
    m.name = src.name;
    const auto& pbr = src.pbrMetallicRoughness;
    requireColor(pbr.baseColorFactor, 4, path + ".pbrMetallicRoughness.baseColorFactor");
    for (int c = 0; c < 4; ++c) m.baseColor[c] = float(pbr.baseColorFactor[c]);
    if (m.baseColor.maxCoeff() > 1.0f) {
      if (clampedBaseColors_++ == 0) firstClamped_ = path;
      m.baseColor = m.baseColor.cwiseMin(1.0f);
    }
    m.baseColorTexture = readSlot(pbr.baseColorTexture, path + ".pbrMetallicRoughness.baseColorTexture");

    requireColor(src.emissiveFactor, 3, path + ".emissiveFactor");
    double strength = 1.0;
    const auto ext = src.extensions.find("KHR_materials_emissive_strength");
    if (ext != src.extensions.end()) {
      const std::string where = path + ".extensions.KHR_materials_emissive_strength";
      strength = number(ext->second, "emissiveStrength", 1.0, where);
      if (strength < 0.0) fail(where + ".emissiveStrength", "must not be negative");
    }
    for (int c = 0; c < 3; ++c) m.emission[c] = float(src.emissiveFactor[c] * strength);
    if (!m.emission.allFinite()) fail(path + ".emissiveFactor", "times emissiveStrength overflows");
    m.emissiveTexture = readSlot(src.emissiveTexture, path + ".emissiveTexture");

    if (src.alphaMode == "OPAQUE" || src.alphaMode.empty()) m.alphaMode = AlphaMode::Opaque;
    else if (src.alphaMode == "MASK") m.alphaMode = AlphaMode::Mask;
    else if (src.alphaMode == "BLEND") m.alphaMode = AlphaMode::Blend;
    else fail(path + ".alphaMode", fmt::format("\"{}\" is not OPAQUE, MASK or BLEND", src.alphaMode));
    if (!std::isfinite(src.alphaCutoff) || src.alphaCutoff < 0.0)
      fail(path + ".alphaCutoff", "must be a finite non-negative number");
    m.alphaCutoff = float(src.alphaCutoff);
    m.doubleSided = src.doubleSided;
    return m;
  }

  TextureSlot readSlot(const tinygltf::TextureInfo& info, const std::string& path) {
    TextureSlot slot;
    if (info.index < 0) return slot;
    if (std::size_t(info.index) >= model_.textures.size())
      fail(path + ".index", fmt::format("refers to texture {}, which does not exist", info.index));
    const tinygltf::Texture& texture = model_.textures[info.index];
    const std::string texturePath = fmt::format("textures[{}]", info.index);
    if (texture.source < 0) {
      warnings_.push_back(fmt::format("{}: {} has no PNG or JPEG source (it needs an image extension this baker does "
                                      "not read); {} uses its factor alone",
                                      file_, texturePath, path));
      return slot;
    }
    if (std::size_t(texture.source) >= model_.images.size())
      fail(texturePath + ".source", fmt::format("refers to image {}, which does not exist", texture.source));
    if (texture.sampler >= 0) {
      if (std::size_t(texture.sampler) >= model_.samplers.size())
        fail(texturePath + ".sampler", fmt::format("refers to sampler {}, which does not exist", texture.sampler));
      const tinygltf::Sampler& s = model_.samplers[texture.sampler];
      const std::string samplerPath = fmt::format("{}: samplers[{}]", file_, texture.sampler);
      slot.sampler.wrapS = wrapMode(s.wrapS, samplerPath + ".wrapS");
      slot.sampler.wrapT = wrapMode(s.wrapT, samplerPath + ".wrapT");
      slot.sampler.nearest = s.magFilter == TINYGLTF_TEXTURE_FILTER_NEAREST;
    }
    slot.texCoord = info.texCoord;
    const auto transform = info.extensions.find("KHR_texture_transform");
    if (transform != info.extensions.end()) readTransform(transform->second, path + ".extensions.KHR_texture_transform", slot);
    // Every set a material names becomes an array per mesh: a bound keeps a forged index
    // from allocating gigabytes.
    if (slot.texCoord < 0 || slot.texCoord >= kMaxTexcoordSets)
      fail(path + ".texCoord", fmt::format("{} is outside 0..{}", slot.texCoord, kMaxTexcoordSets - 1));
    slot.image = decodedImage(texture.source);
    if (slot.image < 0) return TextureSlot{};
    out_.texcoordSets.insert(slot.texCoord);
    return slot;
  }

  // uv' = T · R · S · uv, glTF's order. R turns uv counter-clockwise as the image is seen (v
  // points down the image): u' = u cos r + v sin r, v' = −u sin r + v cos r. That is what the
  // Khronos sample viewer and three.js do; the GLSL in the extension's text, read literally as
  // column-major, would turn the other way.
  void readTransform(const tinygltf::Value& ext, const std::string& path, TextureSlot& slot) const {
    auto pair = [&](const char* key, double fallback) {
      Eigen::Vector2d v(fallback, fallback);
      if (!ext.Has(key)) return v;
      const tinygltf::Value& a = ext.Get(key);
      if (!a.IsArray() || a.ArrayLen() != 2 || !a.Get(0).IsNumber() || !a.Get(1).IsNumber())
        fail(path + "." + key, "must be two numbers");
      v = {a.Get(0).GetNumberAsDouble(), a.Get(1).GetNumberAsDouble()};
      if (!v.allFinite()) fail(path + "." + key, "must be finite");
      return v;
    };
    const Eigen::Vector2d offset = pair("offset", 0.0), scale = pair("scale", 1.0);
    const double rotation = number(ext, "rotation", 0.0, path);
    if (ext.Has("texCoord")) {
      if (!ext.Get("texCoord").IsInt()) fail(path + ".texCoord", "must be an integer");
      slot.texCoord = ext.Get("texCoord").GetNumberAsInt();
    }
    const double c = std::cos(rotation), s = std::sin(rotation);
    slot.uvTransform << float(c * scale.x()), float(s * scale.y()), float(offset.x()),  //
        float(-s * scale.x()), float(c * scale.y()), float(offset.y());
  }

  // The Scene image for glTF image `source`, decoded on first use; -1 when it cannot be read.
  int decodedImage(int source) {
    const auto known = decoded_.find(source);
    if (known != decoded_.end()) return known->second;
    std::optional<ColorImage> image = images_.decode(model_, source, file_, warnings_);
    int slot = -1;
    if (image) {
      slot = int(out_.images.size());
      out_.images.push_back(std::move(*image));
    }
    decoded_.emplace(source, slot);
    return slot;
  }

  const tinygltf::Model& model_;
  const GltfImages& images_;
  const std::string& file_;
  std::vector<std::string>& warnings_;
  GltfMaterials out_;
  std::map<int, int> decoded_;
  int clampedBaseColors_ = 0;
  std::string firstClamped_;
};

}  // namespace

GltfMaterials readMaterials(const tinygltf::Model& model, const GltfImages& images, const std::string& file,
                            std::vector<std::string>& warnings) {
  return MaterialReader(model, images, file, warnings).read();
}

}  // namespace baker
