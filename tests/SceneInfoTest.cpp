#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "tests/GltfTestAssets.h"
#include "tests/TestData.h"

namespace baker {
namespace {

using test::GltfBuilder;

// `baker info --json ARGS` through the real binary; fails the test unless it exits with 0.
nlohmann::json info(const std::string& dir, const std::string& args) {
  const test::ProcessResult run = test::runBaker(dir, "info --json " + args);
  EXPECT_EQ(run.exitCode, 0) << run.err;
  return nlohmann::json::parse(run.out, nullptr, false);
}

TEST(SceneInfo, DescribesAGeneratedScene) {
  const std::string dir = test::makeTempDir("info-generated");
  GltfBuilder gltf;
  const int emissive = gltf.material({{"emissiveFactor", {1, 1, 1}}, {"doubleSided", true}});
  const int mask = gltf.material({{"alphaMode", "MASK"}});
  const int mesh = test::squareMesh(gltf, 1.0f, emissive);
  gltf.node({{"mesh", mesh}});
  gltf.node({{"mesh", mesh}, {"translation", {0, 0, 2}}});
  gltf.node({{"mesh", test::squareMesh(gltf, 1.0f, mask)}, {"translation", {0, 0, 4}}});
  gltf.node({{"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
  gltf.json()["extensions"] = {{"KHR_lights_punctual", {{"lights", nlohmann::json::array({{{"type", "spot"}, {"spot", nlohmann::json::object()}}})}}}};
  gltf.json()["extensionsUsed"] = {"KHR_lights_punctual", "KHR_materials_sheen"};
  gltf.write(dir, "scene");

  const nlohmann::json j = info(dir, "scene.gltf --sky 0.1,0.2,0.3");
  ASSERT_FALSE(j.is_discarded());
  EXPECT_EQ(j["scene"], 0);
  EXPECT_EQ(j["geometry"]["triangles"], 6);
  EXPECT_EQ(j["geometry"]["unique_triangles"], 4);
  EXPECT_EQ(j["geometry"]["instances"], 3);
  EXPECT_EQ(j["geometry"]["instanced_meshes"], 1);
  EXPECT_EQ(j["bounds"]["max"], nlohmann::json({1.0, 1.0, 4.0}));
  EXPECT_EQ(j["materials"]["defined"], 2);
  EXPECT_EQ(j["materials"]["by_alpha_mode"], nlohmann::json({{"opaque", 1}, {"mask", 1}, {"blend", 0}}));
  EXPECT_EQ(j["materials"]["double_sided"], 1);
  EXPECT_EQ(j["lights"]["spot"], 1);
  EXPECT_EQ(j["extensions"]["ignored"], nlohmann::json({"KHR_materials_sheen"}));
  EXPECT_EQ(j["environment"]["kind"], "constant");
  for (const char* effect : {"emission", "punctual_lights", "emissive_lights", "environment", "bounces", "alpha_filters"})
    EXPECT_TRUE(j["effects"][effect]["simulated"]) << effect << ": " << j["effects"][effect].dump();
  EXPECT_NE(j["effects"]["alpha_filters"]["reason"].get<std::string>().find("2 of 6 triangles"), std::string::npos);

  // Without lights of any kind and without --env, those effects are off, with reasons.
  GltfBuilder plain;
  plain.node({{"mesh", plain.mesh({{"POSITION", plain.floats(test::triangleXY(), "VEC3")}})}});
  plain.write(dir, "plain");
  const nlohmann::json p = info(dir, "plain.gltf");
  for (const char* effect : {"emission", "punctual_lights", "emissive_lights", "environment", "alpha_filters"})
    EXPECT_FALSE(p["effects"][effect]["simulated"]) << effect;
  EXPECT_TRUE(p["effects"]["bounces"]["simulated"]) << "the default material is white";
  EXPECT_EQ(p["effects"]["environment"]["reason"], "no environment map or sky was given");
  EXPECT_EQ(p["environment"]["kind"], "none");

  // The text form runs too, with warnings on stderr.
  const test::ProcessResult text = test::runBaker(dir, "info scene.gltf");
  EXPECT_EQ(text.exitCode, 0);
  EXPECT_NE(text.out.find("lights: 1 (point 0, spot 1, directional 0)"), std::string::npos) << text.out;
  EXPECT_NE(text.err.find("KHR_materials_sheen"), std::string::npos) << text.err;
}

struct KhronosExpectation {
  const char* scene;
  int lights, point, opaque, mask, blend;
  std::vector<std::string> ignored;
  bool emission, alphaFilters;
};

TEST(SceneInfo, KhronosSampleScenes) {
  REQUIRE_SHARED_DATA();
  const std::string dir = test::makeTempDir("info-khronos");
  const std::vector<KhronosExpectation> expectations = {
      {"LightsPunctualLamp", 5, 5, 2, 0, 1, {"KHR_materials_transmission"}, true, true},
      {"EmissiveStrengthTest", 0, 0, 6, 0, 0, {}, true, false},
      {"AlphaBlendModeTest", 0, 0, 2, 3, 1, {}, false, true},
  };
  for (const KhronosExpectation& e : expectations) {
    const nlohmann::json j =
        info(dir, "'" + test::sharedDataPath(std::string("scenes/") + e.scene + "/" + e.scene + ".gltf") + "'");
    ASSERT_FALSE(j.is_discarded()) << e.scene;
    EXPECT_EQ(j["lights"]["total"], e.lights) << e.scene;
    EXPECT_EQ(j["lights"]["point"], e.point) << e.scene;
    EXPECT_EQ(j["materials"]["by_alpha_mode"]["opaque"], e.opaque) << e.scene;
    EXPECT_EQ(j["materials"]["by_alpha_mode"]["mask"], e.mask) << e.scene;
    EXPECT_EQ(j["materials"]["by_alpha_mode"]["blend"], e.blend) << e.scene;
    EXPECT_EQ(j["extensions"]["ignored"], nlohmann::json(e.ignored)) << e.scene;
    EXPECT_EQ(j["effects"]["emission"]["simulated"], e.emission) << e.scene;
    EXPECT_EQ(j["effects"]["alpha_filters"]["simulated"], e.alphaFilters) << e.scene;
    EXPECT_GT(j["geometry"]["triangles"].get<int>(), 0) << e.scene;
    EXPECT_GT(j["textures"]["decoded"].get<int>(), 0) << e.scene;
    for (const auto& w : j["warnings"])
      EXPECT_EQ(w.get<std::string>().find("file not found"), std::string::npos) << e.scene << ": " << w;
  }
}

TEST(SceneInfo, BakeAcceptsTheSceneOptions) {
  const std::string dir = test::makeTempDir("info-bake-options");
  GltfBuilder gltf;
  gltf.node({{"mesh", gltf.mesh({{"POSITION", gltf.floats(test::triangleXY(), "VEC3")}})}});
  gltf.write(dir, "scene");
  const test::ProcessResult run = test::runBaker(dir, "scene.gltf --scene 0 --sky 1,1,1 --rays 16 --out out.vdb");
  EXPECT_EQ(run.exitCode, 0) << run.err;
  const test::ProcessResult bad = test::runBaker(dir, "scene.gltf --scene 1 --out bad.vdb");
  EXPECT_EQ(bad.exitCode, 2);
  EXPECT_NE(bad.err.find("--scene 1: scene.gltf: the file has 1 scene(s)"), std::string::npos) << bad.err;
}

}  // namespace
}  // namespace baker
