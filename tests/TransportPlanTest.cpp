#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "basis/BasisRegistry.h"
#include "basis/DirectionSet.h"
#include "basis/GramOperators.h"
#include "basis/ShBasis.h"
#include "formats/VolumeReader.h"
#include "scene/GltfLoader.h"
#include "scene/RayTracer.h"
#include "tests/GltfTestAssets.h"
#include "tests/TestData.h"
#include "tests/TransportTestSupport.h"

// What a bake simulates follows the scene; results follow the seed and nothing else.
namespace baker {
namespace {

using test::GltfBuilder;

// A 4 m floor (ρ 0.5) at z = 0, a double-sided emissive square 2 m above it, an alpha-MASK
// checker square between them and, when `light`, a 5 cd point light: every effect at once.
std::string writeLitScene(const std::string& dir, bool light, bool mask) {
  GltfBuilder gltf;
  const int floor = gltf.material({{"pbrMetallicRoughness", {{"baseColorFactor", {0.5, 0.5, 0.5, 1}}}}});
  const int emitter = gltf.material({{"doubleSided", true},
                                     {"emissiveFactor", {1.0, 0.8, 0.6}},
                                     {"pbrMetallicRoughness", {{"baseColorFactor", {0.2, 0.2, 0.2, 1}}}}});
  gltf.node({{"mesh", test::squareMesh(gltf, 4.0f, floor)}});
  gltf.node({{"mesh", test::squareMesh(gltf, 1.0f, emitter)}, {"translation", {1.5, 1.5, 2}}});
  if (mask) {
    const int texture = gltf.texture(test::encodePng(2, 2, 4, {255, 255, 255, 255, 255, 255, 255, 0, 255, 255, 255, 0,
                                                               255, 255, 255, 255}),
                                     {{"magFilter", 9728}});
    const int fence = gltf.material({{"alphaMode", "MASK"},
                                     {"doubleSided", true},
                                     {"pbrMetallicRoughness", {{"baseColorTexture", {{"index", texture}}}}}});
    gltf.node({{"mesh", test::squareMesh(gltf, 2.0f, fence)}, {"translation", {1, 1, 1}}});
  }
  if (light) {
    gltf.json()["extensionsUsed"] = {"KHR_lights_punctual"};
    gltf.json()["extensions"]["KHR_lights_punctual"]["lights"] = {{{"type", "point"}, {"intensity", 5.0}}};
    gltf.node({{"translation", {3, 1, 1.5}}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
  }
  return gltf.write(dir, "lit");
}

class TransportPlan : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = test::makeTempDir(::testing::UnitTest::GetInstance()->current_test_info()->name()); }
  nlohmann::json bake(const std::string& args) {
    const test::ProcessResult r = test::runBaker(dir_, args + " --json");
    EXPECT_EQ(r.exitCode, 0) << r.err;
    return nlohmann::json::parse(r.out);
  }
  std::string dir_;
};

TEST_F(TransportPlan, EmissiveOnlySceneTracesNoShadowRaysToLights) {
  writeLitScene(dir_, false, false);
  const nlohmann::json j = bake("lit.gltf --spacing 1 --rays 64");
  EXPECT_FALSE(j["plan"]["punctual_lights"]["simulated"].get<bool>());
  EXPECT_FALSE(j["plan"]["direct_punctual"]["simulated"].get<bool>());
  EXPECT_FALSE(j["plan"]["alpha_filters"]["simulated"].get<bool>());
  EXPECT_TRUE(j["plan"]["emissive_lights"]["simulated"].get<bool>());
  EXPECT_EQ(j["rays"]["punctual_shadow"], 0);
  EXPECT_EQ(j["rays"]["direct_punctual_shadow"], 0);
  EXPECT_EQ(j["rays"]["environment_shadow"], 0);
  EXPECT_GT(j["rays"]["emitter_shadow"].get<std::int64_t>(), 0);
  EXPECT_GT(j["rays"]["bounce"].get<std::int64_t>(), 0);
}

TEST_F(TransportPlan, NoSwitchesTurnEffectsOffAndCostNoRays) {
  writeLitScene(dir_, true, true);
  const nlohmann::json all = bake("lit.gltf --spacing 1 --rays 64");
  for (const char* effect : {"emission", "punctual_lights", "emissive_lights", "bounces", "alpha_filters",
                             "direct_punctual", "probe_validity"})
    EXPECT_TRUE(all["plan"][effect]["simulated"].get<bool>()) << effect;
  EXPECT_FALSE(all["plan"]["environment"]["simulated"].get<bool>());
  EXPECT_GT(all["rays"]["punctual_shadow"].get<std::int64_t>(), 0);
  EXPECT_GT(all["rays"]["direct_punctual_shadow"].get<std::int64_t>(), 0);

  const nlohmann::json fewer =
      bake("lit.gltf --spacing 1 --rays 64 --no punctual-lights --no direct_punctual --no emissive-lights --out b.vdb");
  EXPECT_EQ(fewer["rays"]["punctual_shadow"], 0);
  EXPECT_EQ(fewer["rays"]["direct_punctual_shadow"], 0);
  EXPECT_EQ(fewer["rays"]["emitter_shadow"], 0);
  EXPECT_NE(fewer["plan"]["punctual_lights"]["reason"].get<std::string>().find("turned off on request"),
            std::string::npos);

  const nlohmann::json flat = bake("lit.gltf --spacing 1 --rays 64 --bounces 0 --out c.vdb");
  EXPECT_EQ(flat["rays"]["bounce"], 0);
  EXPECT_EQ(flat["rays"]["punctual_shadow"], 0);
  EXPECT_EQ(flat["rays"]["emitter_shadow"], 0);
}

TEST_F(TransportPlan, UnknownEffectIsRefusedWithTheList) {
  writeLitScene(dir_, false, false);
  const test::ProcessResult r = test::runBaker(dir_, "lit.gltf --no sparkles");
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.err.find("--no sparkles: not an effect; effects are emission, punctual-lights"), std::string::npos)
      << r.err;
  EXPECT_EQ(test::runBaker(dir_, "lit.gltf --bounces -1").exitCode, 2);
}

// Bounces, a punctual light, an emissive surface and alpha-masked geometry: the same seed
// gives the same volume, bit for bit, on 1 and 2 threads; another seed gives another.
TEST_F(TransportPlan, VolumesAreBitIdenticalAcrossThreadCounts) {
  writeLitScene(dir_, true, true);
  bake("lit.gltf --spacing 0.5 --rays 64 --threads 1 --seed 5 --out one.vdb");
  bake("lit.gltf --spacing 0.5 --rays 64 --threads 2 --seed 5 --out two.vdb");
  bake("lit.gltf --spacing 0.5 --rays 64 --threads 2 --seed 6 --out other.vdb");
  const Volume one = readVolume(dir_ + "/one.vdb"), two = readVolume(dir_ + "/two.vdb");
  const Volume other = readVolume(dir_ + "/other.vdb");
  ASSERT_GT(one.coefficients.size(), 0u);
  EXPECT_TRUE(one.coefficients == two.coefficients);
  EXPECT_TRUE(one.visibility == two.visibility);
  EXPECT_TRUE(one.states == two.states);
  EXPECT_TRUE(one.offsets == two.offsets);
  EXPECT_FALSE(one.coefficients == other.coefficients);
}

// A point light in an empty scene: the probe's coefficients are the exact projection of
// E(n) = E⊥ max(0, n·ω) into the basis, whatever the basis.
TEST(PunctualAtProbe, CoefficientsAreTheExactProjectionOfTheClampedCosine) {
  const std::string dir = test::makeTempDir("punctual_at_probe");
  GltfBuilder gltf;
  gltf.json()["extensionsUsed"] = {"KHR_lights_punctual"};
  gltf.json()["extensions"]["KHR_lights_punctual"]["lights"] = {
      {{"type", "point"}, {"intensity", 8.0}, {"color", {1.0, 0.5, 0.25}}}};
  gltf.node({{"translation", {0.6, 1.2, -0.8}}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
  const Scene scene = loadGltf(gltf.write(dir, "light"));
  const RayTracer tracer(scene);
  const Eigen::Vector3d toLight = Eigen::Vector3d(0.6, 1.2, -0.8).normalized();
  const double ePerp = 8.0 / Eigen::Vector3d(0.6, 1.2, -0.8).squaredNorm();
  BakeSettings settings;
  settings.rays = 64;

  // sh-l2 keeps bands 0–2 of the clamped cosine: opposite the light E = E⊥(1/4 − 1/2 + 5/16).
  const ShBasis sh(2);
  const test::BakedProbe shProbe = test::bakeProbe(scene, tracer, sh, settings, Eigen::Vector3f::Zero());
  EXPECT_NEAR(sh.reconstruct(shProbe.coefficients.data(), -toLight).x(), ePerp * 0.0625, 1e-5 * ePerp);
  EXPECT_NEAR(sh.reconstruct(shProbe.coefficients.data(), toLight).x(), ePerp * (0.25 + 0.5 + 0.3125), 1e-5 * ePerp);

  // Ambient Dice and SG: moments by a dense quadrature, solved with the exact Gram matrix.
  const DirectionSet dense = sphericalFibonacci(400000);
  for (const char* name : {"ad-rgb", "ad-srbf", "sg-12"}) {
    const auto basis = makeBasis(name);
    const test::BakedProbe probe = test::bakeProbe(scene, tracer, *basis, settings, Eigen::Vector3f::Zero());
    const SphericalFunctions& f = basis->functions(0);
    Eigen::VectorXd moments = Eigen::VectorXd::Zero(f.count());
    std::vector<double> values(f.count());
    for (std::size_t q = 0; q < dense.size(); ++q) {
      f.evaluate(dense.directions[q], values.data());
      const double e = ePerp * std::max(0.0, dense.directions[q].dot(toLight)) * dense.weights[q];
      for (int i = 0; i < f.count(); ++i) moments[i] += e * values[i];
    }
    const Eigen::VectorXd expected = GramOperators(f, name).gramInverse() * moments;
    const double scale = expected.cwiseAbs().maxCoeff();
    for (int i = 0; i < f.count(); ++i)
      EXPECT_NEAR(probe.coefficients[basis->coefficientOffset(0) + i], expected[i], 2e-3 * scale) << name << " " << i;
  }
}

}  // namespace
}  // namespace baker
