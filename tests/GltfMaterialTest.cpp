#include <gtest/gtest.h>

#include <cmath>

#include "scene/ColorImage.h"
#include "scene/GltfLoader.h"
#include "scene/Shading.h"
#include "tests/GltfTestAssets.h"
#include "tests/TestData.h"

namespace baker {
namespace {

using test::GltfBuilder;

constexpr int kNearest = 9728, kLinear = 9729, kClamp = 33071, kMirror = 33648;

// 2 × 2 RGBA texture, rows from the top: red, green / blue, white; alphas 255, 128, 0, 64.
std::vector<unsigned char> quadrantPng() {
  return test::encodePng(2, 2, 4, {255, 0, 0, 255, 0, 255, 0, 128, 0, 0, 255, 0, 255, 255, 255, 64});
}

float srgb(int byte) { return srgbToLinear(byte / 255.0f); }

class GltfMaterials : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = test::makeTempDir(::testing::UnitTest::GetInstance()->current_test_info()->name()); }
  // A unit square with `material`, after any materials the test added.
  Scene load(GltfBuilder& gltf, const nlohmann::json& material) {
    gltf.node({{"mesh", test::squareMesh(gltf, 1.0f, gltf.material(material))}});
    return loadGltf(gltf.write(dir_, "scene"));
  }
  std::string dir_;
};

// The square's texture coordinates are an affine map of position (uv (s, t) sits at
// (s, 1 − t)), so triangle 0, corners (0,0), (1,0), (1,1), reaches any (s, t) with the weights
// u = x − y, v = y of its second and third corners, inside the triangle or not.
Eigen::Vector2f weightsAt(float s, float t) { return {s - (1.0f - t), 1.0f - t}; }

SurfaceSample shadeAt(const Scene& scene, float s, float t) {
  const Eigen::Vector2f w = weightsAt(s, t);
  return shadeSurface(scene, 0, 0, w.x(), w.y());
}

// The scene with every triangle given material `material`.
Scene withMaterial(const Scene& scene, int material) {
  Scene copy = scene;
  for (std::uint32_t& m : copy.meshes[0].triangleMaterial) m = std::uint32_t(material);
  return copy;
}

TEST_F(GltfMaterials, BaseColorIsFactorTimesSrgbTextureTimesVertexColor) {
  GltfBuilder gltf;
  const int texture = gltf.texture(quadrantPng(), {{"magFilter", kNearest}});
  // COLOR_0 is a per-vertex factor: 0.5 everywhere in red, 1 in green and blue.
  const int color = gltf.floats({0.5f, 1, 1, 0.5f, 1, 1, 0.5f, 1, 1, 0.5f, 1, 1}, "VEC3");
  const Scene scene = [&] {
    gltf.node({{"mesh", test::squareMesh(gltf, 1.0f, gltf.material({{"pbrMetallicRoughness",
                                                                       {{"baseColorFactor", {0.8, 0.5, 1.0, 1.0}},
                                                                        {"baseColorTexture", {{"index", texture}}}}}}))}});
    gltf.json()["meshes"][0]["primitives"][0]["attributes"]["COLOR_0"] = color;
    return loadGltf(gltf.write(dir_, "scene"));
  }();
  ASSERT_EQ(scene.images.size(), 1u);
  // uv (0.75, 0.75): bottom-right texel, white.
  const SurfaceSample white = shadeAt(scene, 0.75f, 0.75f);
  EXPECT_NEAR(white.albedo.x(), 0.8f * 0.5f, 1e-6f);
  EXPECT_NEAR(white.albedo.y(), 0.5f, 1e-6f);
  EXPECT_NEAR(white.albedo.z(), 1.0f, 1e-6f);
  EXPECT_EQ(white.alpha, 1.0f) << "OPAQUE ignores alpha";
  // uv (0.9, 0.2): top-right texel, green 255 with sRGB decoding (255 → 1).
  const SurfaceSample green = shadeAt(scene, 0.9f, 0.2f);
  EXPECT_NEAR(green.albedo.y(), 0.5f * srgb(255), 1e-6f);
  EXPECT_NEAR(green.albedo.x(), 0.0f, 1e-6f);
}

TEST_F(GltfMaterials, SrgbDecodingIsExact) {
  EXPECT_FLOAT_EQ(srgb(0), 0.0f);
  EXPECT_FLOAT_EQ(srgb(255), 1.0f);
  EXPECT_NEAR(srgb(10), 10 / 255.0 / 12.92, 1e-7);
  EXPECT_NEAR(srgb(128), std::pow((128 / 255.0 + 0.055) / 1.055, 2.4), 1e-6);
}

TEST_F(GltfMaterials, EmissionIsFactorTimesStrengthTimesTexture) {
  GltfBuilder gltf;
  const int texture = gltf.texture(quadrantPng(), {{"magFilter", kNearest}});
  const Scene scene = load(gltf, {{"emissiveFactor", {1.0, 0.5, 0.25}},
                                  {"emissiveTexture", {{"index", texture}}},
                                  {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", 4.0}}}}}});
  const SurfaceSample white = shadeAt(scene, 0.75f, 0.75f);
  EXPECT_NEAR(white.emission.x(), 4.0f, 1e-5f);
  EXPECT_NEAR(white.emission.y(), 2.0f, 1e-5f);
  EXPECT_NEAR(white.emission.z(), 1.0f, 1e-5f);
  EXPECT_EQ(shadeAt(scene, 0.75f, 0.25f).emission.x(), 0.0f) << "the green texel has no red";
}

TEST_F(GltfMaterials, AlphaModes) {
  GltfBuilder gltf;
  const int texture = gltf.texture(quadrantPng(), {{"magFilter", kNearest}});
  const nlohmann::json textured = {{"baseColorTexture", {{"index", texture}}}};
  gltf.material({{"alphaMode", "MASK"}, {"alphaCutoff", 0.4}, {"pbrMetallicRoughness", textured}});
  gltf.material({{"alphaMode", "BLEND"}, {"pbrMetallicRoughness", textured}});
  const Scene scene = load(gltf, {{"alphaMode", "MASK"}, {"pbrMetallicRoughness", textured}});  // default cutoff 0.5
  ASSERT_EQ(scene.meshes.size(), 1u);
  // Texel alphas at uv: (0.75, 0.25) = 128/255, (0.75, 0.75) = 64/255.
  EXPECT_NEAR(shadeAt(scene, 0.75f, 0.25f).alpha, 128 / 255.0f, 1e-6f);
  auto stops = [&](int material, float s, float t, float xi) {
    const Eigen::Vector2f w = weightsAt(s, t);
    return surfaceStopsRay(withMaterial(scene, material), 0, 0, w.x(), w.y(), xi);
  };
  EXPECT_TRUE(stops(2, 0.75f, 0.25f, 0.0f)) << "MASK 0.5: 128/255 passes the cutoff";
  EXPECT_FALSE(stops(2, 0.75f, 0.75f, 0.0f)) << "MASK 0.5: 64/255 is cut";
  EXPECT_TRUE(stops(0, 0.75f, 0.25f, 0.0f)) << "MASK 0.4: 128/255 stays";
  EXPECT_TRUE(stops(1, 0.75f, 0.25f, 0.49f)) << "BLEND: opaque when xi < alpha";
  EXPECT_FALSE(stops(1, 0.75f, 0.25f, 0.51f));
  EXPECT_EQ(scene.meshes[0].alphaTestedBegin, 0u) << "every triangle is alpha-tested";
}

TEST_F(GltfMaterials, TextureTransformOffsetScaleRotation) {
  GltfBuilder gltf;
  const int texture = gltf.texture(quadrantPng(), {{"magFilter", kNearest}});
  auto slot = [&](const nlohmann::json& transform) {
    return nlohmann::json{{"pbrMetallicRoughness",
                           {{"baseColorTexture", {{"index", texture}, {"extensions", {{"KHR_texture_transform", transform}}}}}}}};
  };
  gltf.material(slot({{"offset", {0.5, 0.0}}}));
  gltf.material(slot({{"scale", {0.5, 0.5}}, {"offset", {0.5, 0.5}}}));
  const Scene scene = load(gltf, slot({{"rotation", M_PI / 2}}));
  auto colorAt = [&](int material, float s, float t) { return shadeAt(withMaterial(scene, material), s, t).albedo; };
  // Offset (0.5, 0): uv (0.25, 0.25) reads (0.75, 0.25), the green texel.
  EXPECT_GT(colorAt(0, 0.25f, 0.25f).y(), 0.99f);
  // Scale ½ then offset ½: uv (0.9, 0.9) reads (0.95, 0.95), white.
  EXPECT_GT(colorAt(1, 0.9f, 0.9f).minCoeff(), 0.99f);
  // Rotation π/2: u' = v, v' = −u, so uv (0.9, 0.25) reads (0.25, −0.9) → (0.25, 0.1) with
  // REPEAT: the red texel; the opposite rotation would read (−0.25, 0.9) → (0.75, 0.9), white.
  const Eigen::Vector3f rotated = colorAt(2, 0.9f, 0.25f);
  EXPECT_GT(rotated.x(), 0.99f) << rotated.transpose();
  EXPECT_LT(rotated.z(), 0.01f) << rotated.transpose();
}

TEST_F(GltfMaterials, SecondTexcoordSet) {
  GltfBuilder gltf;
  const int texture = gltf.texture(quadrantPng(), {{"magFilter", kNearest}});
  const int material = gltf.material({{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", texture}, {"texCoord", 1}}}}}});
  const int mesh = test::squareMesh(gltf, 1.0f, material);
  // TEXCOORD_1 is constant (0.75, 0.75): white everywhere.
  gltf.json()["meshes"][mesh]["primitives"][0]["attributes"]["TEXCOORD_1"] =
      gltf.floats({0.75f, 0.75f, 0.75f, 0.75f, 0.75f, 0.75f, 0.75f, 0.75f}, "VEC2");
  gltf.node({{"mesh", mesh}});
  const Scene scene = loadGltf(gltf.write(dir_, "scene"));
  ASSERT_EQ(scene.meshes[0].texcoords.size(), 2u);
  EXPECT_TRUE(scene.meshes[0].texcoords[0].empty()) << "no material reads set 0";
  EXPECT_GT(shadeAt(scene, 0.1f, 0.1f).albedo.minCoeff(), 0.99f);
}

TEST(ColorImage, WrapModesAndFilters) {
  // 2 × 1 greys 0 and 255 (linear 0 and 1 after sRGB decoding).
  const ColorImage image = ColorImage::fromBytes(2, 1, {0, 0, 0, 255, 255, 255, 255, 255});
  SamplerState s;
  s.nearest = true;
  EXPECT_EQ(image.sample({0.25f, 0.5f}, s).x(), 0.0f);
  EXPECT_EQ(image.sample({1.25f, 0.5f}, s).x(), 0.0f) << "REPEAT";
  s.wrapS = Wrap::MirroredRepeat;
  EXPECT_EQ(image.sample({1.25f, 0.5f}, s).x(), 1.0f) << "MIRRORED_REPEAT: 1.25 reads 0.75";
  EXPECT_EQ(image.sample({-0.25f, 0.5f}, s).x(), 0.0f) << "MIRRORED_REPEAT: −0.25 reads 0.25";
  s.wrapS = Wrap::ClampToEdge;
  EXPECT_EQ(image.sample({7.0f, 0.5f}, s).x(), 1.0f);
  EXPECT_EQ(image.sample({-7.0f, 0.5f}, s).x(), 0.0f);
  EXPECT_EQ(image.sample({std::nanf(""), 0.5f}, s).x(), 0.0f) << "NaN reads as 0";
  // Bilinear: halfway between the texel centres (u = 0.5) is the mean; at a centre, the texel.
  s.nearest = false;
  s.wrapS = Wrap::ClampToEdge;
  EXPECT_FLOAT_EQ(image.sample({0.5f, 0.5f}, s).x(), 0.5f);
  EXPECT_FLOAT_EQ(image.sample({0.75f, 0.5f}, s).x(), 1.0f);
  EXPECT_FLOAT_EQ(image.sample({0.625f, 0.5f}, s).x(), 0.75f);
  s.wrapS = Wrap::Repeat;
  EXPECT_FLOAT_EQ(image.sample({0.0f, 0.5f}, s).x(), 0.5f) << "REPEAT blends the edge texels";
  EXPECT_FLOAT_EQ(image.sample({1e9f + 0.5f, 0.5f}, s).x(), 0.5f) << "huge coordinates stay in range";
}

TEST_F(GltfMaterials, SamplerModesComeFromTheFile) {
  GltfBuilder gltf;
  const int texture = gltf.texture(quadrantPng(), {{"magFilter", kLinear}, {"wrapS", kClamp}, {"wrapT", kMirror}});
  const Scene scene = load(gltf, {{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", texture}}}}}});
  const SamplerState& s = scene.materials[0].baseColorTexture.sampler;
  EXPECT_EQ(s.wrapS, Wrap::ClampToEdge);
  EXPECT_EQ(s.wrapT, Wrap::MirroredRepeat);
  EXPECT_FALSE(s.nearest);
}

}  // namespace
}  // namespace baker
