// NaN, infinities and negative numbers in what a scene brings (float textures, vertex colours,
// light intensities, environment maps) are refused or sanitised with a warning, and never
// reach a volume: each case bakes to finite coefficients or stops with exit code 2.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

#include "basis/BasisRegistry.h"
#include "common/Error.h"
#include "scene/GltfLoader.h"
#include "scene/RayTracer.h"
#include "scene/Shading.h"
#include "tests/GltfTestAssets.h"
#include "tests/TestData.h"
#include "tests/TransportTestSupport.h"

namespace baker {
namespace {

using test::GltfBuilder;

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

class StressInputValues : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = test::makeTempDir(::testing::UnitTest::GetInstance()->current_test_info()->name()); }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  static bool warns(const Scene& scene, const std::string& text) {
    for (const std::string& w : scene.warnings)
      if (w.find(text) != std::string::npos) return true;
    return false;
  }
  // The probe half a unit above the unit square of `scene`, under a white sky, with a bounce:
  // every coefficient must be finite.
  void expectFiniteBake(Scene& scene) const {
    scene.environment = Environment::constant(Eigen::Vector3f::Ones());
    const RayTracer tracer(scene);
    const auto basis = makeBasis("sh-l2");
    const test::BakedProbe probe = test::bakeProbe(scene, tracer, *basis, {}, Eigen::Vector3f(0.5f, 0.5f, 0.5f));
    for (float c : probe.coefficients) ASSERT_TRUE(std::isfinite(c));
  }

  std::string dir_;
};

// glTF textures are PNG or JPEG; an EXR or HDR named as one, with NaN, infinite and negative
// texels, is not decoded: a warning, and the material's factor alone.
TEST_F(StressInputValues, FloatTexturesAreNotReadAndTheFactorIsUsed) {
  const std::vector<float> poisoned = {kNaN, kInf, -1.0f, -kInf, 0.5f, kNaN, 2.0f, 0.0f, -3.0f, 1.0f, 1.0f, 1.0f};
  for (const char* name : {"poisoned.exr", "poisoned.hdr"}) {
    SCOPED_TRACE(name);
    test::writeFloatImage(dir_ + "/" + name, 2, 2, poisoned);
    GltfBuilder gltf;
    gltf.json()["images"] = {{{"uri", name}}};
    gltf.json()["textures"] = {{{"source", 0}}};
    const int material = gltf.material({{"pbrMetallicRoughness",
                                         {{"baseColorFactor", {0.5, 0.25, 1.0, 1.0}}, {"baseColorTexture", {{"index", 0}}}}},
                                        {"emissiveFactor", {1, 1, 1}},
                                        {"emissiveTexture", {{"index", 0}}}});
    gltf.node({{"mesh", test::squareMesh(gltf, 1.0f, material)}});
    Scene scene = loadGltf(gltf.write(dir_, "textured"));
    EXPECT_TRUE(warns(scene, "not a PNG or JPEG image; materials use their factors instead"));
    const SurfaceSample s = shadeSurface(scene, 0, 0, 0.3f, 0.3f);
    EXPECT_EQ(s.albedo, Eigen::Vector3f(0.5f, 0.25f, 1.0f));
    EXPECT_EQ(s.emission, Eigen::Vector3f::Ones());
    expectFiniteBake(scene);
  }
}

// Float COLOR_0 may hold anything: components are clamped to [0, 1] and NaN reads as 1, with
// one warning naming the first.
TEST_F(StressInputValues, VertexColoursOutsideZeroToOneAreClampedWithAWarning) {
  GltfBuilder gltf;
  const int positions = gltf.floats({0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0}, "VEC3");
  const int colors = gltf.floats({0.5f, 0.5f, 0.5f, 1.0f,  // fine
                                  kNaN, 0.2f, 0.3f, 1.0f,  //
                                  kInf, -kInf, 5.0f, -1.0f,  //
                                  -0.5f, 0.25f, 1.5f, kNaN},
                                 "VEC4");
  gltf.node({{"mesh", gltf.mesh({{"POSITION", positions}, {"COLOR_0", colors}}, gltf.indices({0, 1, 2, 0, 2, 3}))}});
  Scene scene = loadGltf(gltf.write(dir_, "colours"));
  EXPECT_TRUE(warns(scene, "3 COLOR_0 colour(s) had components outside [0, 1] or not a number (first: "
                           "meshes[0].primitives[0].attributes.COLOR_0[1]); clamped to [0, 1], NaN read as 1"));
  const std::vector<Eigen::Vector4f>& c = scene.meshes[0].colors;
  ASSERT_EQ(c.size(), 4u);
  EXPECT_EQ(c[0], Eigen::Vector4f(0.5f, 0.5f, 0.5f, 1.0f));
  EXPECT_EQ(c[1], Eigen::Vector4f(1.0f, 0.2f, 0.3f, 1.0f));
  EXPECT_EQ(c[2], Eigen::Vector4f(1.0f, 0.0f, 1.0f, 0.0f));
  EXPECT_EQ(c[3], Eigen::Vector4f(0.0f, 0.25f, 1.0f, 1.0f));
  expectFiniteBake(scene);
}

// Non-finite or negative intensities are refused, and so is one that is a finite double but
// infinite as the float light is carried in (it would turn every path it reaches into Inf).
TEST_F(StressInputValues, LightIntensitiesOutsideSinglePrecisionAreRefused) {
  // JSON has no NaN or infinity; the nearest a file can come, 1e400, stops the JSON parser.
  struct Case {
    const char *intensity, *color, *refusal;
  };
  const Case cases[] = {{"-1", "[1, 1, 1]", "lights[0].intensity must be finite and non-negative"},
                        {"1e400", "[1, 1, 1]", "number overflow parsing '1e400'"},
                        {"1e39", "[1, 1, 1]", "lights[0].intensity 1e+39 times .color is beyond single precision"},
                        {"1e30", "[1e10, 1, 1]", "lights[0].intensity 1e+30 times .color is beyond single precision"}};
  for (const auto& [intensity, color, refusal] : cases) {
    SCOPED_TRACE(intensity);
    GltfBuilder gltf;
    gltf.json()["extensionsUsed"] = {"KHR_lights_punctual"};
    gltf.json()["extensions"]["KHR_lights_punctual"]["lights"] = {
        {{"type", "point"}, {"intensity", "@intensity"}, {"color", "@color"}}};
    gltf.node({{"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
    const std::string path = gltf.write(dir_, "light");
    std::string text;
    std::getline(std::ifstream(path), text, '\0');
    text.replace(text.find("\"@intensity\""), 12, intensity);
    text.replace(text.find("\"@color\""), 8, color);
    std::ofstream(path) << text;
    try {
      loadGltf(path);
      ADD_FAILURE() << "accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(refusal), std::string::npos) << e.what();
    }
  }
}

// An environment map's NaN, infinite and negative texels read as 0 with a warning, and the bake
// stays finite; a multiplier or a texel times it beyond single precision stops with exit 2.
TEST_F(StressInputValues, EnvironmentMapsAreSanitisedOrRefused) {
  std::vector<float> sky(16 * 8 * 3, 1.0f);
  sky[0] = kNaN;
  sky[4] = kInf;
  sky[8] = -2.0f;
  test::writeFloatImage(dir_ + "/sky.exr", 16, 8, sky);
  const std::string room = "'" + test::sourcePath("data/default_room/default_room.gltf") + "'";
  const test::ProcessResult sanitised = test::runBaker(dir_, room + " --env sky.exr --rays 16 --spacing 2 --out ok.vdb");
  EXPECT_EQ(sanitised.exitCode, 0) << sanitised.err;
  EXPECT_NE(sanitised.err.find("3 texel(s) were negative or not finite and read as 0"), std::string::npos);
  EXPECT_TRUE(std::filesystem::exists(dir_ + "/ok.vdb"));  // and finite: the bake refuses to write otherwise

  const test::ProcessResult huge = test::runBaker(dir_, room + " --env sky.exr --env-intensity 1e39 --out no.vdb");
  EXPECT_EQ(huge.exitCode, 2);
  EXPECT_NE(huge.err.find("--env-intensity must be a finite non-negative number within single precision"),
            std::string::npos)
      << huge.err;

  sky[30] = 3e38f;
  test::writeFloatImage(dir_ + "/bright.exr", 16, 8, sky);
  const test::ProcessResult overflow =
      test::runBaker(dir_, room + " --env bright.exr --env-intensity 10 --out no.vdb");
  EXPECT_EQ(overflow.exitCode, 2);
  EXPECT_NE(overflow.err.find("--env-intensity 10 takes texel (10, 0) of bright.exr beyond single precision"),
            std::string::npos)
      << overflow.err;
  EXPECT_FALSE(std::filesystem::exists(dir_ + "/no.vdb"));
}

}  // namespace
}  // namespace baker
