// The library's entry point, in process: a request's every bad value is refused before anything
// is loaded, as a SettingError naming the request's own field; a job's volume records what made
// it; single probes are traced as the grid's are.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "bake/BakeJob.h"
#include "cli/CommandLine.h"
#include "common/Error.h"
#include "formats/VolumeHeader.h"
#include "tests/TestData.h"

namespace baker {
namespace {

BakeRequest roomRequest() {
  BakeRequest request;
  request.scenePath = test::sourcePath("data/default_room/default_room.gltf");
  request.quality.clear();
  request.rays = 16;
  request.spacing = 1.0;
  return request;
}

// The field the request's validation names, or "" when it accepts the request.
std::string refusedSetting(const std::function<void(BakeRequest&)>& change) {
  BakeRequest request = roomRequest();
  change(request);
  try {
    validateBakeRequest(request);
  } catch (const SettingError& e) {
    return e.setting();
  }
  return "";
}

TEST(BakeJob, EveryBadValueIsRefusedNamingItsField) {
  EXPECT_EQ(refusedSetting([](BakeRequest&) {}), "");
  EXPECT_EQ(refusedSetting([](BakeRequest& r) { r.spacing = 0.0; }), "spacing");
  EXPECT_EQ(refusedSetting([](BakeRequest& r) { r.spacing = -1.0; }), "spacing");
  EXPECT_EQ(refusedSetting([](BakeRequest& r) { r.rays = 0; }), "rays");
  EXPECT_EQ(refusedSetting([](BakeRequest& r) { r.rays = kMaxRaysPerProbe + 1; }), "rays");
  EXPECT_EQ(refusedSetting([](BakeRequest& r) { r.quality = "best"; }), "quality");
  EXPECT_EQ(refusedSetting([](BakeRequest& r) { r.bounces = kMaxBounces + 1; }), "bounces");
  EXPECT_EQ(refusedSetting([](BakeRequest& r) { r.threads = -1; }), "threads");
  EXPECT_EQ(refusedSetting([](BakeRequest& r) { r.window.hannWidth = -1; }), "window");
  EXPECT_EQ(refusedSetting([](BakeRequest& r) { r.turnedOff = {"sparkles"}; }), "turned_off");
  EXPECT_EQ(refusedSetting([](BakeRequest& r) { r.basis = "sh-l99"; }), "basis");
  EXPECT_EQ(refusedSetting([](BakeRequest& r) { r.sgSharpness = 4.0; }), "sg_sharpness");
  EXPECT_EQ(refusedSetting([](BakeRequest& r) { r.basis = "sg-12", r.sgSharpness = -1.0; }), "sg_sharpness");
  EXPECT_EQ(refusedSetting([](BakeRequest& r) { r.nonNegative = true; }), "non_negative");  // sh-l2 changes sign
  EXPECT_EQ(refusedSetting([](BakeRequest& r) { r.basis = "ad-srbf", r.nonNegative = true; }), "");
  EXPECT_EQ(refusedSetting([](BakeRequest& r) { r.sharedReflectionCell = -0.1; }), "share_reflections");
  EXPECT_EQ(refusedSetting([](BakeRequest& r) { r.sharedReflectionCell = std::nan(""); }), "share_reflections");
  EXPECT_EQ(refusedSetting([](BakeRequest& r) { r.sharedReflectionCell = 0.1; }), "");
  EXPECT_EQ(refusedSetting([](BakeRequest& r) { r.sharedReflectionCell = 0.1, r.quality = "draft"; }),
            "share_reflections");  // a preset's rounds follow each probe's own noise
  // A preset makes the ray count irrelevant.
  EXPECT_EQ(refusedSetting([](BakeRequest& r) { r.quality = "draft", r.rays = 0; }), "");
}

// The command line says each refused setting as its flag.
TEST(BakeJob, TheCommandLineNamesTheFlagOfASetting) {
  EXPECT_EQ(flagOf("sg_sharpness"), "--sg-sharpness");
  EXPECT_EQ(flagOf("turned_off"), "--no");
  EXPECT_EQ(commandLineMessage(SettingError("spacing", "must be positive, got -1")), "--spacing must be positive, got -1");
  EXPECT_EQ(commandLineMessage(SettingError("turned_off", "x: not an effect")), "--no x: not an effect");
  EXPECT_EQ(commandLineMessage(InputError("a.gltf: broken")), "a.gltf: broken");
}

// A basis a file names is the file's content, not a setting: its error names the file.
TEST(BakeJob, AFilesUnknownBasisIsTheFilesErrorNotASetting) {
  try {
    basisInFile("sh-l99", {}, "old.vdb");
    FAIL() << "sh-l99 is not a basis";
  } catch (const SettingError& e) {
    FAIL() << "a setting error would print as a flag: " << e.what();
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("old.vdb: basis 'sh-l99' is not a basis", 0), 0u) << e.what();
  }
}

TEST(BakeJob, TheVolumeRecordsWhatMadeItAndProbesAtMatchTheGrid) {
  BakeRequest request = roomRequest();
  request.seed = 5;
  const BakeJob job(request);
  BakeStats stats;
  const Volume volume = job.bake(&stats);
  EXPECT_EQ(volume.basisName, "sh-l2");
  EXPECT_EQ(volume.grid.probeCount(), stats.probes);
  EXPECT_EQ(volume.settings.at("rays"), "16");
  EXPECT_EQ(volume.settings.at("quality"), "fixed");
  EXPECT_EQ(volume.settings.at("seed"), "5");
  EXPECT_EQ(volume.settings.at("scene"), "default_room.gltf");
  EXPECT_EQ(volume.settings.at("scene_fnv1a64").size(), 16u);
  EXPECT_EQ(volume.settings.at("sampler"), ProbeBaker::kSampler);
  EXPECT_EQ(volume.settings.at("effect.bounces"), "on");
  EXPECT_EQ(job.rayLimit(), 16);
  // 16 rays fit sky visibility to SH band 1 only: its band-2 coefficients are zero in exact
  // arithmetic and must be stored as zeros, not as the quadrature's ±1e-17.
  ASSERT_EQ(volume.visibilityPerProbe, 9);
  for (std::size_t row = 0; row * 9 < volume.visibility.size(); ++row)
    for (int f = 4; f < 9; ++f) ASSERT_EQ(volume.visibility[row * 9 + f], 0.0f) << "row " << row << ", coefficient " << f;

  // A probe placed where the grid puts one is placed the same way.
  const Eigen::Vector3f at = volume.grid.position(1, 1, 1).cast<float>();
  const BakedProbes probes = job.probesAt({at});
  ASSERT_EQ(probes.placements.size(), 1u);
  const std::int64_t index = volume.grid.linearIndex(1, 1, 1);
  EXPECT_EQ(probes.placements[0].state, volume.states[index]);
  EXPECT_EQ(probes.placements[0].offset, volume.offsets[index]);
  EXPECT_EQ(probes.samples[0].radiance.size(), 16u);
  EXPECT_EQ(probes.coefficientsPerProbe, volume.coefficientsPerProbe);
}

TEST(BakeJob, AQualityPresetRecordsItsTargetAndLimits) {
  BakeRequest request = roomRequest();
  request.quality = "draft";
  request.spacing = 2.0;
  const BakeJob job(request);
  const Volume volume = job.bake();
  EXPECT_EQ(volume.settings.at("quality"), "draft");
  EXPECT_EQ(volume.settings.at("target_error"), "0.05");
  EXPECT_EQ(volume.settings.at("max_rays"), std::to_string(job.rayLimit()));
  EXPECT_EQ(job.rayLimit(), 7680);
  EXPECT_EQ(volume.settings.at("sampler"), ProbeBaker::kAdaptiveSampler);
}

}  // namespace
}  // namespace baker
