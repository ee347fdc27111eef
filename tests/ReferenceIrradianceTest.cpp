#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "bake/ProbeBaker.h"
#include "bake/ProbesAt.h"
#include "bake/TransportPlan.h"
#include "basis/ShBasis.h"
#include "scene/GltfLoader.h"
#include "scene/RayTracer.h"
#include "scene/SceneCensus.h"
#include "scene/SceneEffects.h"
#include "scene/SceneOptions.h"
#include "tests/SeedStatistics.h"
#include "tests/TestData.h"
#include "volume/ProbeGrid.h"

// The baker against Blender Cycles: irradiance at the probes of the reference scenes, for the
// six axis normals, from `baker probe`'s samples (no basis). Cycles' values and how they were
// made are in ../shared/data/reference/ and tests/reference/ (each file's settings[*].commands).
#if defined(__SANITIZE_ADDRESS__)
#define BAKER_SANITIZED 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define BAKER_SANITIZED 1
#endif
#endif

namespace baker {
namespace {

const char* const kAxes[6] = {"+x", "-x", "+y", "-y", "+z", "-z"};
const Eigen::Vector3f kNormals[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};

// The shared references, and the project's own.
std::string referencePath(const std::string& scene) {
  const std::string own = test::sourcePath("tests/reference/" + scene + ".json");
  if (std::filesystem::exists(own)) return own;
  return test::sharedDataPath("reference/" + scene + ".json");
}

nlohmann::json readJson(const std::string& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

// A reference's scene file and environment map: the project's own (data/), else shared; "" when
// neither exists.
std::string existing(const std::string& own, const std::string& shared) {
  if (std::filesystem::exists(own)) return own;
  return !shared.empty() && std::filesystem::exists(shared) ? shared : "";
}
std::string scenePath(const nlohmann::json& ref) {
  const std::string name = ref["scene"], file = ref["gltf"];
  return existing(test::sourcePath("data/" + name + "/" + file),
                  test::sharedDataPath("scenes/" + name + "/" + file));
}
std::string environmentPath(const nlohmann::json& ref) {
  if (!ref.contains("env_settings") || !ref["env_settings"].is_object()) return "";
  const std::string file = ref["env_settings"]["file"];
  return existing(test::sourcePath("data/" + std::filesystem::path(file).stem().string() + "/" + file),
                  test::sharedDataPath("hdri/" + file));
}

Scene referenceScene(const nlohmann::json& ref) {
  Scene scene = loadGltf(scenePath(ref));
  if (ref.contains("env_settings") && ref["env_settings"].is_object()) {
    const nlohmann::json& env = ref["env_settings"];
    SceneOptions options;
    options.environmentMap = environmentPath(ref);
    options.environmentIntensity = env.value("strength", 1.0);
    options.environmentRotation = env.value("rotation_deg", 0.0);
    std::vector<std::string> warnings;
    scene.environment = environmentFromOptions(options, warnings);
  }
  return scene;
}

// E(n) at every probe for the six axes, as `baker probe --no direct-punctual` bakes it.
// `quality`: a preset of qualityPresets() in place of a fixed `rays`.
std::vector<std::vector<Eigen::Vector3f>> bakeAxes(const Scene& scene, const RayTracer& tracer,
                                                    const std::vector<Eigen::Vector3f>& probes, int rays, int bounces,
                                                    std::uint64_t seed, const char* quality = nullptr,
                                                    float sharedReflectionCell = 0.0f) {
  std::vector<PlannedEffect> plan = planEffects(scene, takeCensus(scene));
  turnOffEffects(plan, {"direct-punctual"});
  BakeSettings settings;
  settings.rays = rays;
  if (quality) {
    const QualityPreset* preset = findQualityPreset(quality);
    settings.rays = preset->rays;
    settings.convergence = preset->convergence;
  }
  settings.transport = transportSettings(plan, bounces, seed);
  const ShBasis basis(2);
  settings.sharedReflectionCell = sharedReflectionCell;
  const ProbeBaker baker(scene, tracer, basis, settings, 1);
  std::vector<ProbeTask> tasks;
  for (std::size_t i = 0; i < probes.size(); ++i) tasks.push_back({probes[i], std::uint64_t(i), 0});
  if (sharedReflectionCell > 0.0f) {
    // Shared with the probes of a grid 1 m apart, as in a volume bake (those inside geometry left out).
    const ProbeGrid grid = makeProbeGrid(scene.bounds, 1.0, 1000);
    std::vector<Eigen::Vector3f> positions;
    for (std::int64_t p = 0; p < grid.probeCount(); ++p) positions.push_back(grid.position(p).cast<float>());
    for (const ProbeTask& task : neighbourTasks(tracer, settings.transport, grid.spacing, positions, tasks.size(), nullptr))
      tasks.push_back(task);
  }
  std::vector<float> coefficients(tasks.size() * baker.coefficientsPerProbe());
  std::vector<float> visibility(tasks.size() * baker.visibilityPerProbe());
  std::vector<ProbeSamples> samples;
  RayCounts counts;
  baker.bake(tasks, coefficients.data(), visibility.data(), &counts, &samples);
  std::vector<std::vector<Eigen::Vector3f>> out(probes.size());
  for (std::size_t i = 0; i < probes.size(); ++i)
    for (const Eigen::Vector3f& n : kNormals) out[i].push_back(sampledIrradiance(samples[i], n));
  return out;
}

using test::overSeeds;

// Rays per probe at which four seeds' standard error falls under 1 % of the scale on every
// entry (scripts/reference_misses.py reports the variance per ray): the lamp's probes see spots
// a few centimetres from a light through the shade's rim, and the window room's the sun's patch
// through the window, the noisiest light of these scenes.
int testRays(const std::string& scene) {
  return scene == "LightsPunctualLamp" || scene == "window_room" ? 262144 : 65536;
}

struct Case {
  std::string scene;
  int setting;
};
std::ostream& operator<<(std::ostream& out, const Case& c) { return out << c.scene << "_setting" << c.setting; }

class ReferenceIrradiance : public ::testing::TestWithParam<Case> {};

// Every probe, axis and channel: the mean of four independent seeds lies within 2 % of
// S = |E| + ½·(the probe's mean E over the axes) of Cycles' E, plus three standard errors, and
// that standard error is under 1 % of S.
// A reference scene, its setting and its probes, or a reason to skip.
struct Reference {
  nlohmann::json ref;
  Scene scene;
  std::vector<Eigen::Vector3f> probes;
  const nlohmann::json& setting(int index) const { return ref["settings"][index]; }
};

// The project's own references (scene, map and Cycles values in this repository) run without
// ../shared; the others skip without it.
std::string readReference(const Case& c, Reference* out) {
  const std::string path = referencePath(c.scene);
  const std::string skip = "../shared/data is not next to this checkout: skipping the Cycles reference " + c.scene;
  if (!std::filesystem::exists(path)) return skip;
  out->ref = readJson(path);
  if (scenePath(out->ref).empty()) return skip;
  if (out->ref.contains("env_settings") && out->ref["env_settings"].is_object() && environmentPath(out->ref).empty())
    return skip;
  out->scene = referenceScene(out->ref);
  for (const auto& p : out->ref["probes"])
    out->probes.emplace_back(p[0].get<float>(), p[1].get<float>(), p[2].get<float>());
  return "";
}

// Calls check(probe, axis, channel, Cycles' E, S) for every entry of the setting whose scale
// S = |E| + ½·(the probe's mean E over the axes, that channel) is positive; returns how many.
template <typename Check>
int forEachEntry(const nlohmann::json& setting, std::size_t probes, Check check) {
  int entries = 0;
  for (std::size_t p = 0; p < probes; ++p)
    for (int channel = 0; channel < 3; ++channel) {
      double probeMean = 0.0;
      for (const char* axis : kAxes) probeMean += setting["irradiance_axes"][p][axis][channel].get<double>() / 6.0;
      for (int a = 0; a < 6; ++a) {
        const double expected = setting["irradiance_axes"][p][kAxes[a]][channel].get<double>();
        const double scale = std::abs(expected) + 0.5 * probeMean;
        if (!(scale > 0.0)) continue;
        ++entries;
        check(p, a, channel, expected, scale);
      }
    }
  return entries;
}

// The entries where the seeds' mean misses Cycles by more than 2 % of the scale S plus three
// standard errors, or where their standard error is 1 % of S or more, one line each ("" when
// none). Fails the test when the setting has no entry.
std::string missesOverSeeds(const nlohmann::json& setting, std::size_t probes,
                            const std::vector<std::vector<std::vector<Eigen::Vector3f>>>& seeds) {
  std::ostringstream misses;
  const int entries = forEachEntry(setting, probes, [&](std::size_t p, int a, int channel, double expected,
                                                       double scale) {
    std::vector<double> values;
    for (const auto& run : seeds) values.push_back(run[p][a][channel]);
    const test::SeedStatistics s = overSeeds(values);
    if (std::abs(s.mean - expected) > 0.02 * scale + 3.0 * s.standardError || s.standardError >= 0.01 * scale)
      misses << "  probe " << p << " E(" << kAxes[a] << ") " << "rgb"[channel] << ": Cycles " << expected
             << ", mean of " << seeds.size() << " seeds " << s.mean << " (" << 100.0 * (s.mean - expected) / scale
             << " % of S), standard error " << 100.0 * s.standardError / scale << " % of S\n";
  });
  EXPECT_GT(entries, 0);
  return misses.str();
}

TEST_P(ReferenceIrradiance, FourSeedsMatchCyclesOnEveryProbeAxisAndChannel) {
#ifdef BAKER_SANITIZED
  GTEST_SKIP() << "millions of paths per case: run in the optimised build only (the same code is checked "
                  "under the sanitizers by the transport tests)";
#endif
  const Case c = GetParam();
  Reference reference;
  if (const std::string skip = readReference(c, &reference); !skip.empty()) GTEST_SKIP() << skip;
  const nlohmann::json& setting = reference.setting(c.setting);
  const Scene& scene = reference.scene;
  const RayTracer tracer(scene);
  const std::vector<Eigen::Vector3f>& probes = reference.probes;
  const int rays = testRays(c.scene);
  std::vector<std::vector<std::vector<Eigen::Vector3f>>> seeds;
  for (std::uint64_t seed = 1; seed <= 4; ++seed)
    seeds.push_back(bakeAxes(scene, tracer, probes, rays, setting["baker_bounces"].get<int>(), seed));

  const std::string misses = missesOverSeeds(setting, probes.size(), seeds);
  EXPECT_TRUE(misses.empty()) << c.scene << ", " << setting["baker_bounces"] << " reflection(s), " << rays
                              << " rays, seeds 1-4:\n"
                              << misses;
}

// Probes sharing their reflections over cells of 10 cm (`--share-reflections 0.1`) with a grid
// of neighbours: the cells' bias stays within the same tolerance on two scenes with light that
// varies across surfaces (the Cornell box's shadows; two rooms lit through a doorway, the wall
// between them seen from both sides), at a quarter of the rays the unshared test needs.
TEST(ReferenceIrradiance, SharedReflectionsMatchCyclesOnEveryProbeAxisAndChannel) {
#ifdef BAKER_SANITIZED
  GTEST_SKIP() << "millions of paths per case: run in the optimised build only";
#endif
  for (const Case& c : {Case{"cornell_box", 1}, Case{"two_rooms", 1}}) {  // three reflections: setting 0 has one
    Reference reference;
    if (const std::string skip = readReference(c, &reference); !skip.empty()) GTEST_SKIP() << skip;
    const nlohmann::json& setting = reference.setting(c.setting);
    const RayTracer tracer(reference.scene);
    const int rays = testRays(c.scene) / 4;
    std::vector<std::vector<std::vector<Eigen::Vector3f>>> seeds;
    for (std::uint64_t seed = 1; seed <= 4; ++seed)
      seeds.push_back(bakeAxes(reference.scene, tracer, reference.probes, rays, setting["baker_bounces"].get<int>(),
                               seed, nullptr, 0.1f));
    const std::string misses = missesOverSeeds(setting, reference.probes.size(), seeds);
    EXPECT_TRUE(misses.empty()) << c.scene << ", shared reflections, " << rays << " rays, seeds 1-4:\n" << misses;
  }
}

// What a user gets from `baker SCENE` with no sampling flags (quality "default", seed 0): one
// bake within 5 % of S of Cycles on every probe, axis and channel.
TEST_P(ReferenceIrradiance, DefaultQualityBakeIsWithinFivePercentOnEveryProbeAxisAndChannel) {
#ifdef BAKER_SANITIZED
  GTEST_SKIP() << "up to a quarter of a million paths per probe: run in the optimised build only";
#endif
  const Case c = GetParam();
  Reference reference;
  if (const std::string skip = readReference(c, &reference); !skip.empty()) GTEST_SKIP() << skip;
  const nlohmann::json& setting = reference.setting(c.setting);
  const RayTracer tracer(reference.scene);
  const auto baked = bakeAxes(reference.scene, tracer, reference.probes, 0, setting["baker_bounces"].get<int>(), 0,
                              "default");
  std::ostringstream misses;
  const int entries = forEachEntry(setting, reference.probes.size(), [&](std::size_t p, int a, int channel,
                                                                       double expected, double scale) {
    const double miss = (baked[p][a][channel] - expected) / scale;
    if (std::abs(miss) > 0.05)
      misses << "  probe " << p << " E(" << kAxes[a] << ") " << "rgb"[channel] << ": Cycles " << expected
             << ", default bake " << baked[p][a][channel] << " (" << 100.0 * miss << " % of S)\n";
  });
  EXPECT_GT(entries, 0);
  EXPECT_TRUE(misses.str().empty()) << c.scene << ", " << setting["baker_bounces"]
                                    << " reflection(s), quality default, seed 0:\n"
                                    << misses.str();
}

INSTANTIATE_TEST_SUITE_P(Cycles, ReferenceIrradiance,
                         ::testing::Values(Case{"cornell_box", 0}, Case{"cornell_box", 1}, Case{"cornell_lights", 0},
                                           Case{"cornell_lights", 1}, Case{"two_rooms", 0}, Case{"two_rooms", 1},
                                           Case{"LightsPunctualLamp", 0}, Case{"LightsPunctualLamp", 1},
                                           Case{"sunlit_yard", 0}, Case{"sunlit_yard", 1},
                                           Case{"sunlit_yard_low_sun", 0}, Case{"sunlit_yard_low_sun", 1},
                                           Case{"window_room", 0}, Case{"window_room", 1}),
                         [](const ::testing::TestParamInfo<Case>& info) {
                           std::ostringstream name;
                           name << info.param;
                           return name.str();
                         });

// Seeds are independent: each draws its own lattice rotation and direct-view samples, so the
// mean over seeds at R rays and at 2R estimate the same irradiance, within three combined
// standard errors, on a probe that sees small bright spots (LightsPunctualLamp's second probe,
// beside the shade of a 15 cd light). With one fixed lattice for every seed, R = 16384 and
// 32768 differed there by 9 % while seeds agreed to 0.01 %.
TEST(ReferenceIrradiance, MeansOverSeedsAgreeAtRAndTwiceR) {
#ifdef BAKER_SANITIZED
  GTEST_SKIP() << "millions of paths: run in the optimised build only";
#endif
  if (test::sharedDataPath("").empty()) GTEST_SKIP() << "../shared/data is not next to this checkout: skipping";
  const Scene scene = loadGltf(test::sharedDataPath("scenes/LightsPunctualLamp/LightsPunctualLamp.gltf"));
  const RayTracer tracer(scene);
  const std::vector<Eigen::Vector3f> probe = {{-0.7f, 1.0f, 0.7f}};
  std::vector<std::vector<double>> atR(18), atTwiceR(18);
  for (std::uint64_t seed = 1; seed <= 8; ++seed) {
    const auto r = bakeAxes(scene, tracer, probe, 16384, 1, seed);
    const auto twice = bakeAxes(scene, tracer, probe, 32768, 1, 100 + seed);
    for (int a = 0; a < 6; ++a)
      for (int c = 0; c < 3; ++c) {
        atR[a * 3 + c].push_back(r[0][a][c]);
        atTwiceR[a * 3 + c].push_back(twice[0][a][c]);
      }
  }
  int compared = 0;
  for (int k = 0; k < 18; ++k) {
    const test::SeedStatistics x = overSeeds(atR[k]), y = overSeeds(atTwiceR[k]);
    if (!(std::abs(x.mean) + std::abs(y.mean) > 1e-4)) continue;  // an axis facing away from all light
    ++compared;
    EXPECT_GT(x.standardError, 0.0) << "seeds that agree exactly are not independent";
    EXPECT_LE(std::abs(x.mean - y.mean), 3.0 * std::hypot(x.standardError, y.standardError))
        << "E(" << kAxes[k / 3] << ") " << "rgb"[k % 3] << ": " << x.mean << " ± " << x.standardError << " at 16384 rays, "
        << y.mean << " ± " << y.standardError << " at 32768";
  }
  EXPECT_GE(compared, 9);
}

}  // namespace
}  // namespace baker
