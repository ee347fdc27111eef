// Light adds up: baking a·A + b·B gives a·bake(A) + b·bake(B), for two lighting setups A and B.
// Exactly so, to float rounding, wherever the samples do not depend on the lighting: punctual
// lights through every bounce while the same lights are aimed at (their shadow rays draw no
// random numbers, and the aims of one light do not depend on its intensity), and a sky scaled
// by --env-intensity (its sampling table only scales). Two different skies are sampled each by
// its own luminance, so their sum holds in expectation, over independent seeds.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "bake/Baker.h"
#include "basis/BasisRegistry.h"
#include "basis/ShBasis.h"
#include "scene/GltfLoader.h"
#include "scene/RayTracer.h"
#include "tests/GltfTestAssets.h"
#include "tests/TestData.h"
#include "tests/TransportTestSupport.h"

namespace baker {
namespace {

constexpr double kA = 0.3, kB = 2.5;

// A smooth gradient sky and one with two bright spots, 32 × 16 texels.
std::vector<float> skyMap(bool spots) {
  std::vector<float> rgb(32 * 16 * 3);
  for (int j = 0; j < 16; ++j)
    for (int i = 0; i < 32; ++i)
      for (int c = 0; c < 3; ++c)
        rgb[3 * (j * 32 + i) + c] = spots ? ((i == 5 && j == 4) || (i == 20 && j == 9) ? 40.0f + c : 0.1f)
                                          : 0.2f + 0.05f * float(j) + 0.1f * float(c) + 0.01f * float(i);
  return rgb;
}

class StressLinearity : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = test::makeTempDir("stress-linearity");
    for (const char* file : {"default_room.gltf", "default_room.bin"})
      std::filesystem::copy_file(test::sourcePath(std::string("data/default_room/") + file), dir_ + "/" + file);
    settings_.rays = 64;
    settings_.transport.emission = settings_.transport.emissiveLights = false;  // the panel is no setup's
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  std::string writeSky(const std::string& name, const std::vector<float>& rgb) const {
    const std::string path = dir_ + "/" + name + ".exr";
    test::writeFloatImage(path, 32, 16, rgb);
    return path;
  }
  // default_room with a point light and a directional light of the given intensities.
  std::string writeRoomWithLights(double point, double directional) const {
    nlohmann::json room;
    std::ifstream(dir_ + "/default_room.gltf") >> room;
    room["extensionsUsed"].push_back("KHR_lights_punctual");
    room["extensions"]["KHR_lights_punctual"]["lights"] = {
        {{"type", "point"}, {"color", {1.0, 0.8, 0.6}}, {"intensity", point}},
        {{"type", "directional"}, {"color", {0.5, 0.7, 1.0}}, {"intensity", directional}}};
    room["nodes"].push_back({{"translation", {0.5, 2.0, 1.0}}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
    room["nodes"].push_back(
        {{"rotation", {-0.3826834, 0.0, 0.0, 0.9238795}}, {"extensions", {{"KHR_lights_punctual", {{"light", 1}}}}}});
    room["scenes"][0]["nodes"] = {0, 1, 2};
    const std::string path = dir_ + "/lit_room.gltf";
    std::ofstream(path) << room.dump();
    return path;
  }

  std::vector<float> bake(const std::string& scenePath, const SceneOptions& options, const std::string& basisName) {
    const Scene scene = loadGltf(scenePath, options);
    const RayTracer tracer(scene);
    return bakeVolume(scene, tracer, *makeBasis(basisName), makeProbeGrid(scene.bounds, 1.0, 1000), settings_, nullptr)
        .coefficients;
  }

  // combined == a·first + b·second for every coefficient, to float rounding of the largest.
  static void expectLinear(const std::vector<float>& combined, const std::vector<float>& first,
                           const std::vector<float>& second) {
    ASSERT_EQ(combined.size(), first.size());
    ASSERT_EQ(combined.size(), second.size());
    float largest = 0.0f;
    for (float c : combined) largest = std::max(largest, std::abs(c));
    ASSERT_GT(largest, 0.0f);
    float worst = 0.0f;
    for (std::size_t i = 0; i < combined.size(); ++i)
      worst = std::max(worst, std::abs(combined[i] - float(kA * first[i] + kB * second[i])));
    EXPECT_LT(worst, 2e-6f * largest) << "largest coefficient " << largest;
  }

  std::string dir_;
  BakeSettings settings_;
};

TEST_F(StressLinearity, EnvironmentMapsSeenFromTheProbesAddUpOverSeeds) {
  const std::vector<float> gradient = skyMap(false), spots = skyMap(true);
  std::vector<float> mixed(gradient.size());
  for (std::size_t i = 0; i < mixed.size(); ++i) mixed[i] = float(kA * gradient[i] + kB * spots[i]);
  SceneOptions a, b, ab;
  a.environmentMap = writeSky("gradient", gradient);
  b.environmentMap = writeSky("spots", spots);
  ab.environmentMap = writeSky("mixed", mixed);
  const std::string room = dir_ + "/default_room.gltf";
  const Scene scenes[3] = {loadGltf(room, a), loadGltf(room, b), loadGltf(room, ab)};
  const ShBasis basis(2);
  const Eigen::Vector3f normals[3] = {{0, 1, 0}, {0, 0, 1}, {-1, 0, 0}};
  // Per setup, normal and channel: E over eight seeds at two probes.
  const int seeds = 8;
  for (const Eigen::Vector3f& position : {Eigen::Vector3f(0.3f, 1.2f, 1.5f), Eigen::Vector3f(-1.0f, 2.0f, 3.5f)})
    for (const Eigen::Vector3f& n : normals)
      for (int c = 0; c < 3; ++c) {
        double mean[3] = {0, 0, 0}, squares[3] = {0, 0, 0};
        for (int k = 0; k < 3; ++k) {
          const RayTracer tracer(scenes[k]);
          for (int seed = 1; seed <= seeds; ++seed) {
            BakeSettings settings = settings_;
            settings.rays = 256;
            settings.transport.bounces = 0;
            settings.transport.seed = std::uint64_t(seed);
            const double e = sampledIrradiance(test::bakeProbe(scenes[k], tracer, basis, settings, position).samples, n)[c];
            mean[k] += e / seeds;
            squares[k] += e * e / seeds;
          }
        }
        double variance = 0.0;  // of a·mean(A) + b·mean(B) − mean(aA + bB)
        const double factor[3] = {kA, kB, 1.0};
        for (int k = 0; k < 3; ++k)
          variance += factor[k] * factor[k] * (squares[k] - mean[k] * mean[k]) / (seeds - 1);
        EXPECT_NEAR(mean[2], kA * mean[0] + kB * mean[1], 3.0 * std::sqrt(variance) + 1e-5 * mean[2])
            << "probe " << position.transpose() << ", normal " << n.transpose() << ", channel " << c;
      }
}

TEST_F(StressLinearity, PunctualLightsAddUpThroughEveryBounce) {
  settings_.transport.bounces = 3;
  // Both setups keep the point light on, so that it is aimed at alike in all three.
  const double point = 4.0, dimPoint = 1.0, directional = 1.5;
  const std::vector<float> both = bake(writeRoomWithLights(kA * point + kB * dimPoint, kB * directional), {}, "sh-l2");
  const std::vector<float> pointOnly = bake(writeRoomWithLights(point, 0.0), {}, "sh-l2");
  const std::vector<float> dimAndDirectional = bake(writeRoomWithLights(dimPoint, directional), {}, "sh-l2");
  expectLinear(both, pointOnly, dimAndDirectional);
}

TEST_F(StressLinearity, EnvironmentIntensityScalesEveryBounce) {
  settings_.transport.bounces = 3;
  SceneOptions sky, scaled;
  sky.environmentMap = scaled.environmentMap = writeSky("spots", skyMap(true));
  scaled.environmentIntensity = kA;
  const std::string room = dir_ + "/default_room.gltf";
  const std::vector<float> none(bake(room, sky, "sh-l2").size(), 0.0f);
  // a·A + b·0: the second setup is darkness.
  expectLinear(bake(room, scaled, "sh-l2"), bake(room, sky, "sh-l2"), none);
}

}  // namespace
}  // namespace baker
