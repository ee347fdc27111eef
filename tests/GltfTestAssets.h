#pragma once
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>

#include "tests/BakerProcess.h"
#include <vector>

namespace baker::test {

// Builds the small glTF files the scene tests write for themselves: one binary buffer that
// accessors append to, written out as a data: URI (or as a .bin beside the file).
class GltfBuilder {
 public:
  GltfBuilder();

  nlohmann::json& json() { return json_; }
  // An accessor over `values` (float components), e.g. type "VEC3". Returns its index.
  int floats(const std::vector<float>& values, const std::string& type);
  // An accessor of unsigned 32-bit indices.
  int indices(const std::vector<std::uint32_t>& values);
  // An accessor over raw bytes already in glTF layout.
  int raw(const std::vector<std::uint8_t>& bytes, int componentType, const std::string& type, std::size_t count,
          bool normalized);
  // A mesh of one TRIANGLES primitive; `attributes` maps names to accessors. Returns its index.
  int mesh(const nlohmann::json& attributes, int indices = -1, int material = -1);
  // A node (any glTF node JSON) appended to the node list and to scene 0's roots when `root`.
  int node(const nlohmann::json& node, bool root = true);
  int material(const nlohmann::json& material);
  // An image (encoded PNG bytes) as a data: URI, a texture using it with `sampler` (JSON, may
  // be null for none). Returns the texture index.
  int texture(const std::vector<unsigned char>& png, const nlohmann::json& sampler = nullptr);

  // Writes DIR/NAME.gltf with the buffer inside as a data: URI, or as DIR/NAME.bin when
  // `externalBuffer`. Returns the .gltf path.
  std::string write(const std::string& dir, const std::string& name, bool externalBuffer = false) const;
  // Writes DIR/NAME.glb: the JSON chunk, then the buffer as the BIN chunk. Returns its path.
  std::string writeGlb(const std::string& dir, const std::string& name) const;

 private:
  int view(const std::vector<std::uint8_t>& bytes);

  nlohmann::json json_;
  std::vector<std::uint8_t> buffer_;
};

// A triangle in the z = 0 plane, counter-clockwise seen from +Z, as a VEC3 position accessor.
std::vector<float> triangleXY(float size = 1.0f);
// A square [0, size]² in the z = 0 plane, two triangles facing +Z, with positions, TEXCOORD_0
// running (0,0)..(1,1) with v downwards along −y, and indices. Returns the mesh index.
int squareMesh(GltfBuilder& gltf, float size, int material);

std::string base64(const std::vector<unsigned char>& bytes);
// PNG bytes of a `channels`-channel 8-bit image, rows from the top.
std::vector<unsigned char> encodePng(int width, int height, int channels, const std::vector<std::uint8_t>& pixels);
// Writes a float RGB image (rows from the top) in the format `path`'s extension names (.hdr, .exr).
void writeFloatImage(const std::string& path, int width, int height, const std::vector<float>& rgb);


}  // namespace baker::test
