#include <gtest/gtest.h>

#include <cmath>

#include "common/Error.h"
#include "scene/GltfLoader.h"
#include "tests/GltfTestAssets.h"
#include "tests/TestData.h"

namespace baker {
namespace {

using test::GltfBuilder;

class GltfLights : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = test::makeTempDir(::testing::UnitTest::GetInstance()->current_test_info()->name()); }
  // A scene whose lights are `lights`, placed by the nodes `nodes` (each a node JSON without
  // the extension; node k places light k).
  std::string write(const nlohmann::json& lights, std::vector<nlohmann::json> nodes) {
    GltfBuilder gltf;
    for (std::size_t k = 0; k < nodes.size(); ++k) {
      nodes[k]["extensions"] = {{"KHR_lights_punctual", {{"light", k}}}};
      gltf.node(nodes[k]);
    }
    gltf.json()["extensions"] = {{"KHR_lights_punctual", {{"lights", lights}}}};
    gltf.json()["extensionsUsed"] = {"KHR_lights_punctual"};
    return gltf.write(dir_, "lights");
  }
  std::string dir_;
};

TEST_F(GltfLights, PointSpotAndDirectionalFromTheirNodes) {
  const double s = std::sqrt(0.5);
  const Scene scene = loadGltf(write(
      {{{"type", "point"}, {"intensity", 15.0}, {"color", {1.0, 0.5, 0.25}}, {"range", 8.0}, {"name", "bulb"}},
       {{"type", "spot"}, {"intensity", 40.0}, {"spot", {{"innerConeAngle", 0.25}, {"outerConeAngle", 0.5}}}},
       {{"type", "directional"}, {"intensity", 3.0}}},
      {{{"translation", {1, 2, 3}}},
       // Rotated −90° about +X: the node's −Z points down, −Y.
       {{"translation", {0, 4, 0}}, {"rotation", {-s, 0, 0, s}}},
       // Rotated +90° about +Y: −Z turns to −X.
       {{"rotation", {0, s, 0, s}}}}));
  ASSERT_EQ(scene.lights.size(), 3u);
  const PunctualLight& point = scene.lights[0];
  EXPECT_EQ(point.type, PunctualLight::Type::Point);
  EXPECT_EQ(point.name, "bulb");
  EXPECT_EQ(point.node, 0);
  EXPECT_EQ(point.intensity, 15.0f);
  EXPECT_EQ(point.color, Eigen::Vector3f(1.0f, 0.5f, 0.25f));
  EXPECT_EQ(point.range, 8.0f);
  EXPECT_EQ(point.position, Eigen::Vector3f(1, 2, 3));

  const PunctualLight& spot = scene.lights[1];
  EXPECT_EQ(spot.type, PunctualLight::Type::Spot);
  EXPECT_TRUE(std::isinf(spot.range)) << "no range: unlimited";
  EXPECT_EQ(spot.color, Eigen::Vector3f(1, 1, 1)) << "default colour";
  EXPECT_TRUE(spot.position.isApprox(Eigen::Vector3f(0, 4, 0)));
  EXPECT_TRUE(spot.direction.isApprox(Eigen::Vector3f(0, -1, 0), 1e-6f)) << spot.direction.transpose();
  EXPECT_FLOAT_EQ(spot.innerConeAngle, 0.25f);
  EXPECT_FLOAT_EQ(spot.outerConeAngle, 0.5f);

  const PunctualLight& sun = scene.lights[2];
  EXPECT_EQ(sun.type, PunctualLight::Type::Directional);
  EXPECT_TRUE(sun.direction.isApprox(Eigen::Vector3f(-1, 0, 0), 1e-6f)) << sun.direction.transpose();
}

TEST_F(GltfLights, SpotFalloffFollowsTheGltfImplementationNote) {
  PunctualLight spot;
  spot.type = PunctualLight::Type::Spot;
  spot.innerConeAngle = float(20 * M_PI / 180);
  spot.outerConeAngle = float(40 * M_PI / 180);
  EXPECT_FLOAT_EQ(spot.spotFalloff(1.0f), 1.0f);
  EXPECT_FLOAT_EQ(spot.spotFalloff(std::cos(spot.innerConeAngle)), 1.0f);
  EXPECT_FLOAT_EQ(spot.spotFalloff(std::cos(spot.outerConeAngle)), 0.0f);
  EXPECT_FLOAT_EQ(spot.spotFalloff(0.0f), 0.0f);
  // 30°: t = (cos 30° − cos 40°) / (cos 20° − cos 40°), squared.
  const double t = (std::cos(M_PI / 6) - std::cos(2 * M_PI / 9)) / (std::cos(M_PI / 9) - std::cos(2 * M_PI / 9));
  EXPECT_NEAR(spot.spotFalloff(float(std::cos(M_PI / 6))), t * t, 1e-6);
}

TEST_F(GltfLights, MalformedLightsAreRefused) {
  auto rejects = [&](const nlohmann::json& light, const std::string& needle) {
    try {
      loadGltf(write(nlohmann::json::array({light}), {nlohmann::json::object()}));
      ADD_FAILURE() << light.dump();
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("lights.gltf"), std::string::npos) << e.what();
    }
  };
  rejects({{"type", "area"}}, "extensions.KHR_lights_punctual.lights[0].type \"area\"");
  rejects({{"type", "point"}, {"intensity", -1.0}}, "lights[0].intensity must be finite and non-negative");
  rejects({{"type", "spot"}, {"spot", {{"innerConeAngle", 0.6}, {"outerConeAngle", 0.5}}}},
          "lights[0].spot: innerConeAngle 0.6 and outerConeAngle 0.5");
  rejects({{"type", "spot"}, {"spot", {{"outerConeAngle", 2.0}}}}, "lights[0].spot");
  rejects({{"type", "point"}, {"color", {1, -1, 0}}}, "lights[0].color");
  // A node naming a light that does not exist.
  GltfBuilder gltf;
  gltf.node({{"extensions", {{"KHR_lights_punctual", {{"light", 3}}}}}});
  try {
    loadGltf(gltf.write(dir_, "dangling"));
    ADD_FAILURE();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("nodes[0].extensions.KHR_lights_punctual.light refers to light 3"),
              std::string::npos)
        << e.what();
  }
}

// The shared test scenes carry the lights their README describes.
TEST_F(GltfLights, SharedScenesPlaceTheirLights) {
  REQUIRE_SHARED_DATA();
  const Scene spot = loadGltf(test::sharedDataPath("scenes/spot_ground/spot_ground.gltf"));
  ASSERT_EQ(spot.lights.size(), 1u);
  EXPECT_TRUE(spot.lights[0].position.isApprox(Eigen::Vector3f(0, 2, 0)));
  EXPECT_TRUE(spot.lights[0].direction.isApprox(Eigen::Vector3f(0, -1, 0), 1e-6f));
  EXPECT_NEAR(spot.lights[0].innerConeAngle, 20 * M_PI / 180, 1e-6);
  EXPECT_NEAR(spot.lights[0].outerConeAngle, 40 * M_PI / 180, 1e-6);
  const Scene sun = loadGltf(test::sharedDataPath("scenes/sun_ground/sun_ground.gltf"));
  ASSERT_EQ(sun.lights.size(), 1u);
  EXPECT_TRUE(sun.lights[0].direction.isApprox(Eigen::Vector3f(-1, -2, -0.5).normalized(), 1e-5f))
      << sun.lights[0].direction.transpose();
  EXPECT_EQ(sun.lights[0].intensity, 3.0f);
}

}  // namespace
}  // namespace baker
