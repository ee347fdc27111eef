#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>

#include "common/Error.h"
#include "scene/GltfLoader.h"
#include "tests/GltfTestAssets.h"
#include "tests/TestData.h"

namespace baker {
namespace {

using test::GltfBuilder;

class GltfBadInput : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = test::makeTempDir(::testing::UnitTest::GetInstance()->current_test_info()->name()); }

  // Loading must fail with an InputError that names the file and every `needles`.
  void expectRejected(const std::string& path, const std::vector<std::string>& needles) {
    try {
      loadGltf(path);
      ADD_FAILURE() << "loading " << path << " should have failed";
    } catch (const InputError& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find(std::filesystem::path(path).filename().string()), std::string::npos) << message;
      for (const std::string& n : needles) EXPECT_NE(message.find(n), std::string::npos) << message;
      EXPECT_EQ(message.find('\n'), std::string::npos) << "one line: " << message;
    }
  }
  // A scene of one triangle whose positions are `positions`.
  GltfBuilder triangle(const std::vector<float>& positions) {
    GltfBuilder gltf;
    gltf.node({{"mesh", gltf.mesh({{"POSITION", gltf.floats(positions, "VEC3")}})}});
    return gltf;
  }
  std::string dir_;
};

TEST_F(GltfBadInput, NonFinitePosition) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  expectRejected(triangle({0, 0, 0, 1, nan, 0, 0, 1, 0}).write(dir_, "nan"),
                 {"meshes[0].primitives[0].attributes.POSITION[1] is not finite"});
  const float inf = std::numeric_limits<float>::infinity();
  expectRejected(triangle({0, 0, 0, 1, 0, 0, 0, inf, 0}).write(dir_, "inf"),
                 {"meshes[0].primitives[0].attributes.POSITION[2] is not finite"});
}

TEST_F(GltfBadInput, TransformsOverflowingFloats) {
  GltfBuilder gltf = triangle(test::triangleXY());
  gltf.json()["nodes"][0]["scale"] = {1e300, 1, 1};
  expectRejected(gltf.write(dir_, "huge"), {"nodes[0] has a transform beyond floating-point range"});
  GltfBuilder far = triangle(test::triangleXY(100.0f));
  far.json()["nodes"][0]["scale"] = {1e37, 1, 1};
  expectRejected(far.write(dir_, "far"), {"nodes[0] places meshes[0] vertex 1 beyond floating-point range"});
}

TEST_F(GltfBadInput, UrisThatLeaveTheScenesFolder) {
  std::filesystem::create_directories(dir_ + "/inner");
  std::ofstream(dir_ + "/outside.bin") << std::string(36, '\0');
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"../outside.bin", "leaves the scene's folder"},
      {"sub/../../outside.bin", "leaves the scene's folder"},
      {"%2e%2e/outside.bin", "leaves the scene's folder"},
      {dir_ + "/outside.bin", "absolute path"},
      {"file:///etc/hostname", "not a relative file name"},
  };
  nlohmann::json base;
  std::ifstream(triangle(test::triangleXY()).write(dir_ + "/inner", "scene")) >> base;
  for (const auto& [uri, why] : cases) {
    nlohmann::json j = base;
    j["buffers"][0]["uri"] = uri;
    std::ofstream(dir_ + "/inner/scene.gltf") << j.dump();
    expectRejected(dir_ + "/inner/scene.gltf", {"buffers[0].uri", why});
  }
  GltfBuilder withImage = triangle(test::triangleXY());
  withImage.json()["images"] = {{{"uri", "../secret.png"}}};
  expectRejected(withImage.write(dir_ + "/inner", "image"), {"images[0].uri \"../secret.png\" leaves the scene's folder"});
}

TEST_F(GltfBadInput, BufferIsNotTakenFromTheCurrentDirectory) {
  // tinygltf on its own falls back to ./NAME when the scene's folder has no NAME.
  std::filesystem::create_directories(dir_ + "/scene");
  triangle(test::triangleXY()).write(dir_ + "/scene", "tri", true);
  std::filesystem::rename(dir_ + "/scene/tri.bin", dir_ + "/tri.bin");
  const auto cwd = std::filesystem::current_path();
  std::filesystem::current_path(dir_);
  EXPECT_THROW(loadGltf("scene/tri.gltf"), InputError);
  std::filesystem::current_path(cwd);
  expectRejected(dir_ + "/scene/tri.gltf", {"tri.bin"});
}

TEST_F(GltfBadInput, UnsupportedRequiredExtension) {
  GltfBuilder gltf = triangle(test::triangleXY());
  gltf.json()["extensionsUsed"] = {"KHR_draco_mesh_compression"};
  gltf.json()["extensionsRequired"] = {"KHR_draco_mesh_compression"};
  expectRejected(gltf.write(dir_, "draco"), {"extensionsRequired names KHR_draco_mesh_compression"});
}

TEST_F(GltfBadInput, AbsurdCountsAreRefusedBeforeAllocation) {
  GltfBuilder gltf = triangle(test::triangleXY());
  gltf.json()["accessors"][0]["count"] = 1ll << 40;
  expectRejected(gltf.write(dir_, "absurd"), {"meshes[0].primitives[0].attributes.POSITION", "exceeds the limit"});
  // Within the limit but far more than the 36-byte bufferView holds.
  gltf.json()["accessors"][0]["count"] = 20000000;
  expectRejected(gltf.write(dir_, "unbacked"), {"meshes[0].primitives[0].attributes.POSITION", "need 240000000 bytes"});
}

TEST_F(GltfBadInput, AccessorAndViewsOutOfRange) {
  GltfBuilder gltf = triangle(test::triangleXY());
  gltf.json()["meshes"][0]["primitives"][0]["attributes"]["POSITION"] = 7;
  expectRejected(gltf.write(dir_, "noposition"), {"meshes[0].primitives[0].attributes.POSITION refers to accessor 7"});
  GltfBuilder view = triangle(test::triangleXY());
  view.json()["bufferViews"][0]["byteOffset"] = 1000;
  expectRejected(view.write(dir_, "view"), {"bufferViews[0]", "lies outside buffers[0]"});
}

// Cases tinygltf itself rejects before the loader sees the model: the pre-check on the JSON
// names the glTF path instead of tinygltf's bare "primitive indices accessor out of bounds".
TEST_F(GltfBadInput, ReferencesTinygltfWouldRejectWithoutAPath) {
  GltfBuilder indices = triangle(test::triangleXY());
  indices.json()["meshes"][0]["primitives"][0]["indices"] = 7;
  expectRejected(indices.write(dir_, "indices"), {"meshes[0].primitives[0].indices refers to accessor 7"});

  GltfBuilder noView = triangle(test::triangleXY());
  noView.json()["meshes"][0]["primitives"][0]["indices"] = 0;
  noView.json()["accessors"][0].erase("bufferView");
  expectRejected(noView.write(dir_, "noview"), {"accessors[0].bufferView", "meshes[0].primitives[0].indices"});

  GltfBuilder count = triangle(test::triangleXY());
  count.json()["accessors"][0].erase("count");
  expectRejected(count.write(dir_, "count"), {"accessors[0].count is required"});

  GltfBuilder spot = triangle(test::triangleXY());
  spot.json()["extensionsUsed"] = {"KHR_lights_punctual"};
  spot.json()["extensions"]["KHR_lights_punctual"]["lights"] = {{{"type", "spot"}}};
  expectRejected(spot.write(dir_, "spot"), {"extensions.KHR_lights_punctual.lights[0]", "\"spot\""});

  GltfBuilder camera = triangle(test::triangleXY());
  camera.json()["cameras"] = {{{"type", "perspective"}}};
  expectRejected(camera.write(dir_, "camera"), {"cameras[0]", "\"perspective\""});
}

TEST_F(GltfBadInput, MissingBufferFileNamesTheBufferUri) {
  const std::string path = triangle(test::triangleXY()).write(dir_, "external", true);
  std::filesystem::remove(dir_ + "/external.bin");
  expectRejected(path, {"buffers[0].uri \"external.bin\"", "no such file"});
}

// tinygltf converts JSON recursively: 20000 nested brackets overflowed its stack.
TEST_F(GltfBadInput, DeeplyNestedJsonIsRefusedNotACrash) {
  const std::string path = dir_ + "/deep.gltf";
  std::ofstream(path) << "{\"asset\":{\"version\":\"2.0\"},\"extras\":" << std::string(20000, '[')
                      << std::string(20000, ']') << "}";
  expectRejected(path, {"nests deeper than"});
}

// Each texture coordinate set a material names becomes an array per mesh.
TEST_F(GltfBadInput, TexcoordSetIsBounded) {
  GltfBuilder gltf;
  const int texture = gltf.texture(test::encodePng(1, 1, 3, {255, 255, 255}));
  const int material =
      gltf.material({{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", texture}, {"texCoord", 2147483647}}}}}});
  gltf.node({{"mesh", test::squareMesh(gltf, 1.0f, material)}});
  expectRejected(gltf.write(dir_, "texcoord"), {"materials[0].pbrMetallicRoughness.baseColorTexture.texCoord",
                                                "outside 0..31"});
}

// Values tinygltf would drop or misread silently, and a data: URI of the wrong length.
TEST_F(GltfBadInput, MalformedValuesAreNamedNotIgnored) {
  GltfBuilder color = triangle(test::triangleXY());
  color.json()["materials"] = {{{"pbrMetallicRoughness", {{"baseColorFactor", {1, 1, 1}}}}}};
  expectRejected(color.write(dir_, "color"), {"materials[0].pbrMetallicRoughness.baseColorFactor", "4 numbers"});

  GltfBuilder matrix = triangle(test::triangleXY());
  matrix.json()["nodes"][0]["matrix"] = std::vector<double>(15, 0.0);
  expectRejected(matrix.write(dir_, "matrix"), {"nodes[0].matrix", "16 numbers"});

  GltfBuilder version = triangle(test::triangleXY());
  version.json()["asset"]["version"] = "1.0";
  expectRejected(version.write(dir_, "version"), {"asset.version"});

  GltfBuilder length = triangle(test::triangleXY());
  const std::string file = length.write(dir_, "length");
  nlohmann::json json = nlohmann::json::parse(std::ifstream(file));
  json["buffers"][0]["byteLength"] = json["buffers"][0]["byteLength"].get<int>() + 4;
  std::ofstream(file) << json.dump();
  expectRejected(file, {"buffers[0].byteLength", "data: URI holds"});
}

// A point light has no direction, so a zero scale on its node is no error.
TEST_F(GltfBadInput, PointLightOnAZeroScaleNodeLoads) {
  GltfBuilder gltf = triangle(test::triangleXY());
  gltf.json()["extensionsUsed"] = {"KHR_lights_punctual"};
  gltf.json()["extensions"]["KHR_lights_punctual"]["lights"] = {{{"type", "point"}, {"intensity", 1.0}}};
  gltf.node({{"scale", {0, 0, 0}}, {"translation", {0, 2, 0}},
             {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
  const Scene scene = loadGltf(gltf.write(dir_, "point"));
  ASSERT_EQ(scene.lights.size(), 1u);
  EXPECT_EQ(scene.lights[0].position, Eigen::Vector3f(0, 2, 0));
}

TEST_F(GltfBadInput, BadMaterialValues) {
  GltfBuilder gltf = triangle(test::triangleXY());
  gltf.json()["meshes"][0]["primitives"][0]["material"] = gltf.material({{"alphaMode", "CUTOUT"}});
  expectRejected(gltf.write(dir_, "alpha"), {"materials[0].alphaMode \"CUTOUT\""});
  GltfBuilder texture = triangle(test::triangleXY());
  texture.json()["meshes"][0]["primitives"][0]["material"] =
      texture.material({{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 4}}}}}});
  expectRejected(texture.write(dir_, "texture"),
                 {"materials[0].pbrMetallicRoughness.baseColorTexture.index refers to texture 4"});
}

TEST_F(GltfBadInput, MissingTextureIsAWarningAndTheFactorStands) {
  GltfBuilder gltf;
  const int material = gltf.material({{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}});
  gltf.json()["images"] = {{{"uri", "missing.png"}}};
  gltf.json()["textures"] = {{{"source", 0}}};
  gltf.node({{"mesh", test::squareMesh(gltf, 1.0f, material)}});
  const Scene scene = loadGltf(gltf.write(dir_, "scene"));
  ASSERT_EQ(scene.warnings.size(), 1u);
  EXPECT_NE(scene.warnings[0].find("scene.gltf: images[0] (uri \"missing.png\"): file not found"), std::string::npos)
      << scene.warnings[0];
  EXPECT_FALSE(scene.materials[0].baseColorTexture.present());
  // An image that is not PNG or JPEG is the same kind of warning.
  std::ofstream(dir_ + "/missing.png") << "not an image";
  const Scene garbled = loadGltf(gltf.write(dir_, "scene"));
  ASSERT_EQ(garbled.warnings.size(), 1u);
  EXPECT_NE(garbled.warnings[0].find("images[0]: not a PNG or JPEG image"), std::string::npos) << garbled.warnings[0];
}

TEST_F(GltfBadInput, NodeHierarchyMustBeATree) {
  GltfBuilder gltf = triangle(test::triangleXY());
  gltf.node({{"children", {0}}}, false);
  gltf.node({{"children", {0}}}, false);
  expectRejected(gltf.write(dir_, "twoparents"), {"nodes[0] is a child of both nodes[1] and nodes[2]"});
  GltfBuilder cycle = triangle(test::triangleXY());
  cycle.json()["nodes"][0]["children"] = {0};
  expectRejected(cycle.write(dir_, "cycle"), {"nodes[0]"});
}

// Through the real binary, for `bake` and `info`: exit code 2, one line naming file and path.
TEST_F(GltfBadInput, CommandLineExitsWithTwoAndOneLine) {
  triangle({0, 0, 0, 1, std::numeric_limits<float>::quiet_NaN(), 0, 0, 1, 0}).write(dir_, "nan");
  GltfBuilder escape = triangle(test::triangleXY());
  escape.json()["images"] = {{{"uri", "../x.png"}}};
  escape.write(dir_, "escape");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"nan.gltf --out out.vdb", "nan.gltf: meshes[0].primitives[0].attributes.POSITION[1] is not finite"},
      {"info nan.gltf", "nan.gltf: meshes[0].primitives[0].attributes.POSITION[1] is not finite"},
      {"info escape.gltf --json", "escape.gltf: images[0].uri \"../x.png\" leaves the scene's folder"},
      {"escape.gltf --out out.vdb", "images[0].uri"},
      {"info nan.gltf --scene 3", "--scene 3"},
      {"info nan.gltf --sky 1,2", "--sky must be three finite non-negative numbers"},
      {"info nan.gltf --env no_such.hdr", "no_such.hdr"},
  };
  for (const auto& [args, needle] : cases) {
    const test::ProcessResult run = test::runBaker(dir_, args);
    EXPECT_EQ(run.exitCode, 2) << args << ": " << run.err;
    EXPECT_NE(run.err.find(needle), std::string::npos) << args << ": " << run.err;
    EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << args << ": " << run.err;
    EXPECT_FALSE(std::filesystem::exists(dir_ + "/out.vdb")) << args;
  }
}

}  // namespace
}  // namespace baker
