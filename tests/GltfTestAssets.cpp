#include "tests/GltfTestAssets.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace baker::test {
GltfBuilder::GltfBuilder() {
  json_ = {{"asset", {{"version", "2.0"}}},
           {"scene", 0},
           {"scenes", nlohmann::json::array({{{"nodes", nlohmann::json::array()}}})},
           {"nodes", nlohmann::json::array()},
           {"meshes", nlohmann::json::array()},
           {"accessors", nlohmann::json::array()},
           {"bufferViews", nlohmann::json::array()}};
}

int GltfBuilder::view(const std::vector<std::uint8_t>& bytes) {
  while (buffer_.size() % 4) buffer_.push_back(0);  // every accessor starts 4-byte aligned
  json_["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", buffer_.size()}, {"byteLength", bytes.size()}});
  buffer_.insert(buffer_.end(), bytes.begin(), bytes.end());
  return int(json_["bufferViews"].size()) - 1;
}

int GltfBuilder::raw(const std::vector<std::uint8_t>& bytes, int componentType, const std::string& type,
                     std::size_t count, bool normalized) {
  nlohmann::json a = {{"bufferView", view(bytes)}, {"componentType", componentType}, {"count", count}, {"type", type}};
  if (normalized) a["normalized"] = true;
  json_["accessors"].push_back(a);
  return int(json_["accessors"].size()) - 1;
}

int GltfBuilder::floats(const std::vector<float>& values, const std::string& type) {
  const std::size_t components = type == "SCALAR" ? 1 : type == "VEC2" ? 2 : type == "VEC3" ? 3 : type == "VEC4" ? 4 : 16;
  std::vector<std::uint8_t> bytes(values.size() * sizeof(float));
  std::memcpy(bytes.data(), values.data(), bytes.size());
  return raw(bytes, 5126, type, values.size() / components, false);
}

int GltfBuilder::indices(const std::vector<std::uint32_t>& values) {
  std::vector<std::uint8_t> bytes(values.size() * sizeof(std::uint32_t));
  std::memcpy(bytes.data(), values.data(), bytes.size());
  return raw(bytes, 5125, "SCALAR", values.size(), false);
}

int GltfBuilder::mesh(const nlohmann::json& attributes, int indices, int material) {
  nlohmann::json primitive = {{"attributes", attributes}};
  if (indices >= 0) primitive["indices"] = indices;
  if (material >= 0) primitive["material"] = material;
  json_["meshes"].push_back({{"primitives", nlohmann::json::array({primitive})}});
  return int(json_["meshes"].size()) - 1;
}

int GltfBuilder::node(const nlohmann::json& node, bool root) {
  json_["nodes"].push_back(node);
  const int index = int(json_["nodes"].size()) - 1;
  if (root) json_["scenes"][0]["nodes"].push_back(index);
  return index;
}

int GltfBuilder::material(const nlohmann::json& material) {
  json_["materials"].push_back(material);
  return int(json_["materials"].size()) - 1;
}

int GltfBuilder::texture(const std::vector<unsigned char>& png, const nlohmann::json& sampler) {
  json_["images"].push_back({{"uri", "data:image/png;base64," + base64(png)}});
  nlohmann::json texture = {{"source", json_["images"].size() - 1}};
  if (!sampler.is_null()) {
    json_["samplers"].push_back(sampler);
    texture["sampler"] = json_["samplers"].size() - 1;
  }
  json_["textures"].push_back(texture);
  return int(json_["textures"].size()) - 1;
}

std::string GltfBuilder::write(const std::string& dir, const std::string& name, bool externalBuffer) const {
  nlohmann::json out = json_;
  if (!buffer_.empty()) {
    std::string uri = "data:application/octet-stream;base64," + base64(buffer_);
    if (externalBuffer) {
      uri = name + ".bin";
      std::ofstream(dir + "/" + uri, std::ios::binary).write(reinterpret_cast<const char*>(buffer_.data()), buffer_.size());
    }
    out["buffers"] = {{{"byteLength", buffer_.size()}, {"uri", uri}}};
  }
  const std::string path = dir + "/" + name + ".gltf";
  std::ofstream(path) << out.dump();
  return path;
}

std::string GltfBuilder::writeGlb(const std::string& dir, const std::string& name) const {
  nlohmann::json out = json_;
  out["buffers"] = {{{"byteLength", buffer_.size()}}};
  std::string text = out.dump();
  while (text.size() % 4) text += ' ';  // chunks are 4-byte aligned; JSON pads with spaces
  std::vector<std::uint8_t> bin = buffer_;
  while (bin.size() % 4) bin.push_back(0);
  const std::uint32_t header[3] = {0x46546C67u, 2u, std::uint32_t(12 + 8 + text.size() + 8 + bin.size())};
  const std::uint32_t jsonChunk[2] = {std::uint32_t(text.size()), 0x4E4F534Au};
  const std::uint32_t binChunk[2] = {std::uint32_t(bin.size()), 0x004E4942u};
  const std::string path = dir + "/" + name + ".glb";
  std::ofstream file(path, std::ios::binary);
  file.write(reinterpret_cast<const char*>(header), sizeof header);
  file.write(reinterpret_cast<const char*>(jsonChunk), sizeof jsonChunk);
  file.write(text.data(), text.size());
  file.write(reinterpret_cast<const char*>(binChunk), sizeof binChunk);
  file.write(reinterpret_cast<const char*>(bin.data()), bin.size());
  return path;
}

std::vector<float> triangleXY(float size) { return {0, 0, 0, size, 0, 0, 0, size, 0}; }

int squareMesh(GltfBuilder& gltf, float size, int material) {
  const int positions = gltf.floats({0, 0, 0, size, 0, 0, size, size, 0, 0, size, 0}, "VEC3");
  const int uv = gltf.floats({0, 1, 1, 1, 1, 0, 0, 0}, "VEC2");
  return gltf.mesh({{"POSITION", positions}, {"TEXCOORD_0", uv}}, gltf.indices({0, 1, 2, 0, 2, 3}), material);
}

std::string base64(const std::vector<unsigned char>& bytes) {
  static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::uint32_t n = std::uint32_t(bytes[i]) << 16 | (i + 1 < bytes.size() ? bytes[i + 1] << 8 : 0) |
                            (i + 2 < bytes.size() ? bytes[i + 2] : 0);
    out += table[(n >> 18) & 63];
    out += table[(n >> 12) & 63];
    out += i + 1 < bytes.size() ? table[(n >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? table[n & 63] : '=';
  }
  return out;
}

std::vector<unsigned char> encodePng(int width, int height, int channels, const std::vector<std::uint8_t>& pixels) {
  std::vector<unsigned char> png;
  OIIO::Filesystem::IOVecOutput memory(png);
  auto out = OIIO::ImageOutput::create("image.png");
  OIIO::ImageSpec spec(width, height, channels, OIIO::TypeDesc::UINT8);
  spec.attribute("oiio:UnassociatedAlpha", 1);  // the pixels' alpha is straight, as glTF's is
  if (!out || !out->set_ioproxy(&memory) || !out->open("image.png", spec) ||
      !out->write_image(OIIO::TypeDesc::UINT8, pixels.data()) || !out->close())
    throw std::runtime_error("cannot encode a test PNG");
  return png;
}

void writeFloatImage(const std::string& path, int width, int height, const std::vector<float>& rgb) {
  auto out = OIIO::ImageOutput::create(path);
  OIIO::ImageSpec spec(width, height, 3, OIIO::TypeDesc::FLOAT);
  if (!out || !out->open(path, spec) || !out->write_image(OIIO::TypeDesc::FLOAT, rgb.data()) || !out->close())
    throw std::runtime_error("cannot write test image " + path);
}


}  // namespace baker::test
