// Relighting (relight/Relighting.h, volume/SkyTransfer.h): a probe under open sky against the
// sky's irradiance summed here from the map's own texels, the directly seen sky a bake keeps apart
// against a bake without that sky, the same sky giving the bake back bit for bit, relightings that
// compose, a relit volume against a rebake under the new sky within the rebake's own noise, and
// the inputs it refuses.
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>

#include "basis/BasisRegistry.h"
#include "basis/DirectionSet.h"
#include "basis/GramOperators.h"
#include "bake/SkyProjection.h"
#include "common/Error.h"
#include "formats/VdbWriter.h"
#include "formats/VolumeMetadata.h"
#include "formats/VolumeReader.h"
#include "images/RgbImage.h"
#include "relight/Relighting.h"
#include "scene/SceneOptions.h"
#include "tests/BakerProcess.h"
#include "tests/SyntheticVolumes.h"
#include "tests/TestData.h"
#include "tests/VolumeFiles.h"
#include "volume/DistanceMoments.h"

namespace baker {
namespace {

const std::string kLowSun = "data/low_sun_sky/low_sun_sky.hdr";

// One sh-l2 irradiance probe that sees the whole sky (visibility 1 everywhere, in its
// coefficients and its map) under no sky.
AdaptiveVolume openProbe(const Basis& basis) {
  Volume v = test::smoothVolume({2, 2, 2}, {0, 0, 0}, 1.0);
  v.settings = {{"signal", "irradiance"}, {"window", "0"}, {"sky", "none"}};
  std::fill(v.coefficients.begin(), v.coefficients.end(), 0.0f);
  std::fill(v.visibility.begin(), v.visibility.end(), 0.0f);
  for (std::size_t p = 0; p < v.states.size(); ++p) v.visibility[p * v.visibilityPerProbe] = float(std::sqrt(4.0 * M_PI));
  v.distanceMap = {8, 2.5, true};
  v.distanceMoments.assign(v.states.size() * std::size_t(v.distanceMomentsPerProbe()), 1.0f);
  v.sky = SkyRadiance();
  EXPECT_EQ(v.coefficientsPerProbe, basis.totalCoefficients());
  AdaptiveVolume volume;
  volume.levels.push_back(std::move(v));
  return volume;
}

// ∫ L Y_lm dω for l ≤ 2 by the map's own texels (each at its centre, with its exact solid angle),
// with the SH written out (SphericalHarmonicsTest checks the library's against the same formulas).
Eigen::Matrix<double, 9, 3> skyHarmonics(const Environment& env) {
  Eigen::Matrix<double, 9, 3> sum = Eigen::Matrix<double, 9, 3>::Zero();
  const double c0 = 0.5 / std::sqrt(M_PI), c1 = std::sqrt(3.0 / (4 * M_PI)), c2 = 0.5 * std::sqrt(15.0 / M_PI);
  for (int row = 0; row < env.height(); ++row)
    for (int column = 0; column < env.width(); ++column) {
      const Eigen::Vector3d d = env.texelCentre(column, row);
      const double x = d.x(), y = d.y(), z = d.z();
      const double y9[9] = {c0,         c1 * y, c1 * z, c1 * x, c2 * x * y, c2 * y * z,
                            0.25 * std::sqrt(5.0 / M_PI) * (3 * z * z - 1), c2 * x * z, 0.5 * c2 * (x * x - y * y)};
      const Eigen::Vector3d flux = env.texelRadiance(column, row).cast<double>() * env.texelSolidAngle(row);
      for (int k = 0; k < 9; ++k) sum.row(k) += y9[k] * flux.transpose();
    }
  return sum;
}

double clampedCosine(int k) { return k == 0 ? M_PI : k < 4 ? 2.0 * M_PI / 3.0 : M_PI / 4.0; }

// Rays that escape upwards and hit a floor downwards: the map's sky share is 1 where a texel's lobe
// (cos^28, cut at weight 1e-4: 44° wide) lies above the horizon, 0 below, and in between across it.
TEST(Relight, TheDistanceMapHoldsTheSkysShare) {
  const DistanceMapLayout layout{8, 1.0, true};
  DistanceMomentsAccumulator accumulator(layout);
  const DirectionSet rays = sphericalFibonacci(4096);
  std::vector<Eigen::Vector3f> directions;
  std::vector<float> distances;
  for (const Eigen::Vector3d& d : rays.directions) {
    directions.push_back(d.cast<float>());
    distances.push_back(d.y() > 0.0 ? std::numeric_limits<float>::infinity() : 0.5f);
  }
  accumulator.add(directions.data(), distances.data(), int(directions.size()));
  std::vector<float> values(std::size_t(layout.valuesPerProbe()));
  accumulator.write(values.data());
  for (int t = 0; t < layout.texels(); ++t) {
    const double up = layout.texelDirection(t).y(), share = values[std::size_t(2 * layout.texels() + t)];
    if (up > 0.75) EXPECT_EQ(share, 1.0) << t;
    else if (up < -0.75) EXPECT_EQ(share, 0.0) << t;
    else EXPECT_TRUE(share >= 0.0 && share <= 1.0) << t;
  }
}

TEST(Relight, OpenSkyGetsTheSkysIrradiance) {
  const auto basis = makeBasis("sh-l2");
  // A constant sky c: E(n) = π c, whose SH is π c √(4π) in band 0 alone.
  AdaptiveVolume constant = openProbe(*basis);
  relightVolume(constant, *basis, recordSky(Environment::constant({0.5f, 1.0f, 2.0f})), "constant", "open");
  const float* c = constant.levels[0].coefficients.data();
  for (int channel = 0; channel < 3; ++channel) {
    const double radiance = channel == 0 ? 0.5 : channel == 1 ? 1.0 : 2.0;
    EXPECT_NEAR(c[basis->coefficientOffset(channel)], M_PI * radiance * std::sqrt(4.0 * M_PI), 1e-5 * radiance);
    for (int k = 1; k < 9; ++k) EXPECT_NEAR(c[basis->coefficientOffset(channel) + k], 0.0, 1e-5) << k;
  }
  // The low sun: 88 % of its flux in a disk of 1.5°, which the volume's 128 × 64 sky holds in one or
  // two texels of 2.8°: the sun's direction moves by up to ~1.4°, its band-1 terms by sin 1.4° ≈ 2.5 %.
  std::vector<std::string> warnings;
  SceneOptions options;
  options.environmentMap = test::sourcePath(kLowSun);
  const Environment env = environmentFromOptions(options, warnings);
  AdaptiveVolume sun = openProbe(*basis);
  relightVolume(sun, *basis, recordSky(env), skyDescription(env), "open");
  const Eigen::Matrix<double, 9, 3> exact = skyHarmonics(env);
  const float* s = sun.levels[0].coefficients.data();
  for (int channel = 0; channel < 3; ++channel) {
    const double scale = clampedCosine(0) * exact(0, channel);
    for (int k = 0; k < 9; ++k)
      EXPECT_NEAR(s[basis->coefficientOffset(channel) + k], clampedCosine(k) * exact(k, channel), 0.02 * scale)
          << "channel " << channel << " coefficient " << k;
  }
  EXPECT_EQ(sun.levels[0].settings.at("baked_sky"), "none");
  EXPECT_EQ(sun.levels[0].settings.at("sky").rfind("map low_sun_sky.hdr fnv1a64 ", 0), 0u);
}

// A probe over a floor (V = 1 above, 0 below) in a volume without maps, baked with a band window:
// its stored visibility is V's SH times A_l h_l / π (V_00 = √π, V_1,-1 = √(3π)/2, the rest 0), and a
// constant sky c must come out as E_lm = A_l h_l c V_lm: the cosine and the window undone exactly.
TEST(Relight, TheCoefficientsUndoTheCosineAndTheWindow) {
  const auto basis = makeBasis("sh-l2");
  for (const int width : {0, 2}) {
    const BandWindow window{width};
    AdaptiveVolume volume = openProbe(*basis);
    Volume& v = volume.levels[0];
    v.distanceMap = {0, 0.0};
    v.distanceMoments.clear();
    v.settings["window"] = std::to_string(width);
    const double v0 = std::sqrt(M_PI), v1 = std::sqrt(3.0 * M_PI) / 2.0;
    for (std::size_t p = 0; p < v.states.size(); ++p) {
      v.visibility[p * 9] = float(v0);
      v.visibility[p * 9 + 1] = float(2.0 / 3.0 * window.factor(1) * v1);
    }
    relightVolume(volume, *basis, recordSky(Environment::constant({1.0f, 1.0f, 1.0f})), "constant", "floor");
    for (int channel = 0; channel < 3; ++channel) {
      const float* c = v.coefficients.data() + basis->coefficientOffset(channel);
      EXPECT_NEAR(c[0], M_PI * v0, 1e-4) << "window " << width;
      EXPECT_NEAR(c[1], 2.0 * M_PI / 3.0 * window.factor(1) * v1, 1e-4) << "window " << width;
      for (int k = 2; k < 9; ++k) EXPECT_NEAR(c[k], 0.0, 1e-4) << "window " << width << " coefficient " << k;
    }
  }
}

void bake(const std::string& dir, std::vector<std::string> args, const std::string& bounces = "0") {
  args.insert(args.begin(), test::sourcePath("data/default_room/default_room.gltf"));
  for (const std::string& a : {std::string("--bounces"), bounces, std::string("--spacing"), std::string("1"),
                               std::string("--quiet")})
    args.push_back(a);
  const test::ProcessResult run = test::runBaker(dir, args);
  ASSERT_EQ(run.exitCode, 0) << run.err;
}

test::ProcessResult relight(const std::string& dir, std::vector<std::string> args) {
  args.insert(args.begin(), "relight");
  return test::runBaker(dir, args);
}

float largestMagnitude(const std::vector<float>& values) {
  float largest = 0.0f;
  for (const float v : values) largest = std::max(largest, std::abs(v));
  return largest;
}

float largestDifference(const std::vector<float>& a, const std::vector<float>& b) {
  EXPECT_EQ(a.size(), b.size());
  float largest = 0.0f;
  for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) largest = std::max(largest, std::abs(a[i] - b[i]));
  return largest;
}

// default_room under the low sun or a constant sky, --bounces 0. Lit by the sky alone, all a
// probe sees is the sky directly: skyDirect must be the coefficients. With its emissive panel too,
// coefficients − skyDirect must be the panel's light as a bake without the sky finds it (the
// panel's samples and the lattice's share of them do not depend on the sky). For fixed lattices
// and radiance fits; adaptive rounds, whose count follows the light, only alone.
TEST(Relight, TheBakeKeepsTheSkyItSawDirectlyApart) {
  const std::string dir = test::makeTempDir("RelightSkyDirect");
  const std::string sun = test::sourcePath(kLowSun);
  struct Way {
    std::vector<std::string> flags;
    bool sameRays;  // whether the panel's samples do not depend on the sky
  };
  const std::vector<Way> ways = {{{"--rays", "64"}, true},
                                 {{"--rays", "64", "--signal", "radiance", "--basis", "ad-srbf"}, true},
                                 {{"--quality", "draft"}, false}};
  const auto flags = [](std::vector<std::string> a, const std::vector<std::string>& b) {
    a.insert(a.end(), b.begin(), b.end());
    return a;
  };
  for (const Way& way : ways)
    for (const std::vector<std::string>& sky : {std::vector<std::string>{"--env", sun}, {"--sky", "0.5,0.7,0.9"}}) {
      const std::string what = way.flags[1] + " " + sky[1];
      bake(dir, flags(flags(way.flags, sky), {"--no", "emission", "--out", "sky.vdb"}));
      const Volume alone = readVolume(dir + "/sky.vdb");
      ASSERT_TRUE(alone.keepsSkyDirect) << what;
      const float scale = largestMagnitude(alone.coefficients);
      EXPECT_GT(scale, 0.0f);
      EXPECT_LT(largestDifference(alone.skyDirect, alone.coefficients), 1e-6f * scale) << what;
      if (!way.sameRays) continue;
      bake(dir, flags(flags(way.flags, sky), {"--out", "lit.vdb"}));
      bake(dir, flags(way.flags, {"--no", "environment", "--out", "dark.vdb"}));
      const Volume lit = readVolume(dir + "/lit.vdb"), dark = readVolume(dir + "/dark.vdb");
      EXPECT_FALSE(dark.keepsSkyDirect) << "a bake the sky does not light keeps no sky_direct grids";
      std::vector<float> rest = lit.coefficients;
      for (std::size_t i = 0; i < rest.size(); ++i) rest[i] -= lit.skyDirect[i];
      EXPECT_LT(largestDifference(rest, dark.coefficients), 2e-6f * largestMagnitude(lit.coefficients)) << what;
    }
}

// With bounces, a probe lit by the sky alone (the panel neither seen nor lighting surfaces) receives the sky's light seen directly or off
// surfaces and nothing else: skyDirect + skyBounced must be the coefficients, for fixed lattices,
// radiance fits and adaptive rounds. At --bounces 0 there is no light off surfaces to keep.
TEST(Relight, TheBakeKeepsTheSkysLightOffSurfacesApart) {
  const std::string dir = test::makeTempDir("RelightSkyBounced");
  for (const std::vector<std::string>& way : {std::vector<std::string>{"--rays", "64"},
                                              {"--rays", "64", "--signal", "radiance", "--basis", "ad-srbf"},
                                              {"--quality", "draft", "--basis", "ad-ycocg"}}) {
    std::vector<std::string> args = way;
    args.insert(args.end(),
                {"--env", test::sourcePath(kLowSun), "--no", "emission", "--no", "emissive-lights", "--out", "sky.vdb"});
    bake(dir, args, "2");
    const Volume v = readVolume(dir + "/sky.vdb");
    ASSERT_TRUE(v.keepsSkyDirect && v.keepsSkyBounced) << way[1];
    std::vector<float> parts = v.skyDirect;
    for (std::size_t i = 0; i < parts.size(); ++i) parts[i] += v.skyBounced[i];
    const float scale = largestMagnitude(v.coefficients);
    EXPECT_LT(largestDifference(parts, v.coefficients), 2e-6f * scale) << way[1];
    EXPECT_GT(largestMagnitude(v.skyBounced), 0.02f * scale) << way[1] << ": the room's walls light it";
  }
  bake(dir, {"--sky", "1,1,1", "--rays", "16", "--out", "direct.vdb"});
  EXPECT_FALSE(readVolume(dir + "/direct.vdb").keepsSkyBounced) << "no light off surfaces at --bounces 0";
}

// A sky scaled per channel by k: every probe's flux through its map scales by k, so its light off
// surfaces must scale by k exactly (by the luminance's ratio for a YCoCg basis, whose chroma has
// functions of its own). And with that light, relightings A → B → C still equal A → C.
TEST(Relight, ScalesTheSkysLightOffSurfacesToTheNewSky) {
  const std::string dir = test::makeTempDir("RelightScaledBounce");
  const Eigen::Vector3d from(0.5, 0.7, 0.9), k(2.0, 3.0, 1.0);
  for (const std::string basisName : {"sh-l2", "ad-ycocg"}) {
    bake(dir, {"--basis", basisName, "--sky", "0.5,0.7,0.9", "--rays", "64", "--out", "baked.vdb"}, "1");
    const test::ProcessResult run = relight(dir, {"baked.vdb", "--sky", "1,2.1,0.9", "--out", "relit.vdb", "--json"});
    ASSERT_EQ(run.exitCode, 0) << run.err;
    EXPECT_TRUE(nlohmann::json::parse(run.out).at("bounce_scaled").get<bool>());
    const Volume baked = readVolume(dir + "/baked.vdb"), relit = readVolume(dir + "/relit.vdb");
    ASSERT_TRUE(relit.keepsSkyBounced);
    // The light that is neither part, the panel's, stays as baked.
    std::vector<float> restBaked = baked.coefficients, restRelit = relit.coefficients;
    for (std::size_t i = 0; i < restBaked.size(); ++i) {
      restBaked[i] -= baked.skyDirect[i] + baked.skyBounced[i];
      restRelit[i] -= relit.skyDirect[i] + relit.skyBounced[i];
    }
    EXPECT_LT(largestDifference(restRelit, restBaked), 1e-5f * largestMagnitude(relit.coefficients)) << basisName;
    const std::unique_ptr<Basis> basis = makeBasis(basisName);
    const Eigen::Vector3d luminance(0.25, 0.5, 0.25);
    const float largest = largestMagnitude(baked.skyBounced);
    ASSERT_GT(largest, 0.0f);
    for (std::int64_t row = 0; row < baked.rows.count(baked.grid); ++row)
      for (int c = 0; c < 3; ++c) {
        const double factor =
            basis->colorSpace() == ColorSpace::YCoCg ? luminance.dot(k.cwiseProduct(from)) / luminance.dot(from) : k[c];
        for (int f = 0; f < basis->coefficientCount(c); ++f) {
          const std::size_t i = std::size_t(row * baked.coefficientsPerProbe + basis->coefficientOffset(c) + f);
          ASSERT_NEAR(relit.skyBounced[i], factor * baked.skyBounced[i], 1e-5 * largest) << basisName << " " << row;
        }
      }
  }
  bake(dir, {"--env", test::sourcePath(kLowSun), "--rays", "64", "--out", "sun.vdb"}, "1");
  ASSERT_EQ(relight(dir, {"sun.vdb", "--sky", "0.3,0.4,0.5", "--out", "there.vdb"}).exitCode, 0);
  ASSERT_EQ(relight(dir, {"there.vdb", "--sky", "0.9,0.2,0.1", "--out", "onward.vdb"}).exitCode, 0);
  ASSERT_EQ(relight(dir, {"sun.vdb", "--sky", "0.9,0.2,0.1", "--out", "straight.vdb"}).exitCode, 0);
  const Volume onward = readVolume(dir + "/onward.vdb"), straight = readVolume(dir + "/straight.vdb");
  const float largest = largestMagnitude(straight.coefficients);
  EXPECT_LT(largestDifference(onward.coefficients, straight.coefficients), 1e-5f * largest);
  EXPECT_LT(largestDifference(onward.skyBounced, straight.skyBounced), 1e-5f * largest);
  // A shard's part knows only its own probes' view of the sky, not the whole bake's mean.
  bake(dir, {"--sky", "0.5,0.7,0.9", "--rays", "16", "--shard", "0/2", "--out", "part.vdb"}, "1");
  const test::ProcessResult part = relight(dir, {"part.vdb", "--sky", "1,1,1", "--out", "part_relit.vdb"});
  EXPECT_EQ(part.exitCode, 2) << part.err;
  EXPECT_NE(part.err.find("part.vdb: is a shard's part"), std::string::npos) << part.err;
  EXPECT_FALSE(std::filesystem::exists(dir + "/part_relit.vdb"));
}

// Probes whose maps see the whole sky: each one's flux is the sky's whole flux, as is the level's
// mean, so the light off surfaces must scale by ∫L_new / ∫L_old per channel, summed here over the
// recorded skies' texels: the low sun's taken away, a constant sky of 1, 2, 3 put in.
TEST(Relight, OpenProbesScaleTheirLightOffSurfacesByTheSkysWholeFlux) {
  const std::unique_ptr<Basis> basis = makeBasis("sh-l2");
  AdaptiveVolume volume = openProbe(*basis);
  Volume& v = volume.levels.front();
  std::vector<std::string> warnings;
  SceneOptions sun, constant;
  sun.environmentMap = test::sourcePath(kLowSun);
  constant.sky = "1,2,3";
  v.sky = recordSky(environmentFromOptions(sun, warnings));
  const SkyRadiance newSky = recordSky(environmentFromOptions(constant, warnings));
  v.keepsSkyDirect = v.keepsSkyBounced = true;
  v.skyDirect.assign(v.coefficients.size(), 0.0f);
  for (std::size_t i = 0; i < v.coefficients.size(); ++i) v.skyBounced.push_back(0.1f + 0.01f * float(i % 17));
  const std::vector<float> before = v.skyBounced;
  const auto wholeFlux = [](const SkyRadiance& sky) {
    Eigen::Vector3d flux = Eigen::Vector3d::Zero();
    for (int row = 0; row < sky.height; ++row)
      for (int column = 0; column < sky.width; ++column)
        flux += sky.texel(column, row).cast<double>() *
                latLongSolidAngle(1.0 / sky.width, double(row) / sky.height, double(row + 1) / sky.height);
    return flux;
  };
  const Eigen::Vector3d ratio = wholeFlux(newSky).cwiseQuotient(wholeFlux(*v.sky));
  EXPECT_TRUE(relightVolume(volume, *basis, newSky, "constant 1,2,3", "open").bounceScaled);
  for (std::size_t i = 0; i < before.size(); ++i) {
    const int channel = int(i % std::size_t(v.coefficientsPerProbe)) / basis->coefficientCount(0);
    ASSERT_NEAR(v.skyBounced[i], before[i] * ratio[channel], 1e-4 * before[i] * ratio[channel]) << i;
  }
}

// Decoders relight at run time as E_rest(n) + V(n)·E_sky(n) (`validate --run-time-sky` reads a
// volume so). Under a constant sky c, V(n)·πc is exactly the sky's light as the bake projects it,
// so the low sun's bake read under c is the rebake under c to float rounding (with --bounces 0,
// whose panel light the two bakes sample alike).
TEST(Relight, RelitAtRunTimeUnderAConstantSkyIsTheRebake) {
  const std::string dir = test::makeTempDir("RelightRunTime");
  bake(dir, {"--env", test::sourcePath(kLowSun), "--rays", "64", "--out", "sun.vdb"});
  bake(dir, {"--sky", "0.5,0.7,0.9", "--rays", "64", "--out", "constant.vdb"});
  const test::ProcessResult run =
      test::runBaker(dir, {"validate", "constant.vdb", "sun.vdb", "--run-time-sky", "0.5,0.7,0.9", "--json"});
  ASSERT_NE(run.exitCode, 2) << run.err;
  const nlohmann::json report = nlohmann::json::parse(run.out);
  EXPECT_EQ(report.at("run_time_sky"), "constant 0.5,0.7,0.9");
  EXPECT_LT(report.at("error_of_level").at("max").get<double>(), 1e-5);
  const test::ProcessResult stored = test::runBaker(dir, {"validate", "constant.vdb", "sun.vdb", "--json"});
  EXPECT_GT(nlohmann::json::parse(stored.out).at("error_of_level").at("max").get<double>(), 0.1) << "the sun's light";
}

// Adaptive placement: a finer level's border probes take the coarser levels' light, sky_direct
// included, and parts baked as shards merge into the one-process bake byte for byte. Lit by the
// sky alone, every level's sky_direct is its coefficients.
TEST(Relight, AdaptiveLevelsAndTheirPartsKeepTheSkyApart) {
  const std::string dir = test::makeTempDir("RelightAdaptive");
  const std::vector<std::string> flags = {"--placement", "adaptive", "--levels", "2", "--spacing", "0.3",
                                          "--rays", "16", "--no", "emission", "--sky", "0.5,0.7,0.9"};
  const auto bakeAdaptive = [&](std::initializer_list<std::string> more) {
    std::vector<std::string> args = {test::sourcePath("data/default_room/default_room.gltf"), "--bounces", "0", "--quiet"};
    args.insert(args.end(), flags.begin(), flags.end());
    args.insert(args.end(), more);
    const test::ProcessResult run = test::runBaker(dir, args);
    ASSERT_EQ(run.exitCode, 0) << run.err;
  };
  bakeAdaptive({"--out", "whole.vdb"});
  bakeAdaptive({"--shard", "0/2", "--out", "part0.vdb"});
  bakeAdaptive({"--shard", "1/2", "--out", "part1.vdb"});
  const test::ProcessResult merged = test::runBaker(dir, {"merge", "merged.vdb", "part0.vdb", "part1.vdb"});
  ASSERT_EQ(merged.exitCode, 0) << merged.err;
  test::expectSameFiles(dir + "/merged.vdb", dir + "/whole.vdb");
  const AdaptiveVolume whole = readLevels(dir + "/whole.vdb");
  ASSERT_EQ(whole.levels.size(), 2u);
  for (const Volume& level : whole.levels) {
    ASSERT_TRUE(level.keepsSkyDirect);
    EXPECT_TRUE(std::count(level.states.begin(), level.states.end(), ProbeState::Interpolated) > 0 ||
                &level == &whole.levels.front());
    EXPECT_LT(largestDifference(level.skyDirect, level.coefficients), 1e-6f * largestMagnitude(level.coefficients));
  }
}

TEST(Relight, TheSameSkyGivesTheBakeBackAndRelightingsCompose) {
  const std::string dir = test::makeTempDir("RelightSameSky");
  const std::string sky = test::sourcePath(kLowSun);
  bake(dir, {"--env", sky, "--rays", "64", "--out", "baked.vdb"});
  ASSERT_EQ(relight(dir, {"baked.vdb", "--env", sky, "--out", "same.vdb"}).exitCode, 0);
  const Volume baked = readVolume(dir + "/baked.vdb"), same = readVolume(dir + "/same.vdb");
  const auto bits = [](const std::vector<float>& values) {
    return std::string(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(float));
  };
  EXPECT_TRUE(bits(baked.coefficients) == bits(same.coefficients));
  EXPECT_TRUE(bits(baked.visibility) == bits(same.visibility));
  EXPECT_EQ(same.settings.at("sky"), baked.settings.at("sky"));
  EXPECT_EQ(same.settings.at("baked_sky"), baked.settings.at("sky"));

  // Through another sky or straight there: the same volume, since the light the sky does not
  // send directly is kept as it is and the directly seen sky is replaced.
  ASSERT_EQ(relight(dir, {"baked.vdb", "--sky", "0.3,0.4,0.5", "--out", "there.vdb"}).exitCode, 0);
  const test::ProcessResult onward = relight(dir, {"there.vdb", "--sky", "0.9,0.2,0.1", "--out", "onward.vdb", "--json"});
  ASSERT_EQ(onward.exitCode, 0) << onward.err;
  ASSERT_EQ(relight(dir, {"baked.vdb", "--sky", "0.9,0.2,0.1", "--out", "straight.vdb"}).exitCode, 0);
  const nlohmann::json report = nlohmann::json::parse(onward.out);
  EXPECT_EQ(report.at("from_sky"), "constant 0.3,0.4,0.5");
  EXPECT_EQ(report.at("baked_sky"), baked.settings.at("sky"));
  EXPECT_EQ(report.at("old_sky_removed").get<std::string>().rfind("exactly", 0), 0u);
  EXPECT_EQ(report.at("keeps").size(), 1u) << "the emissive panel's light";
  const Volume there = readVolume(dir + "/there.vdb"), onwards = readVolume(dir + "/onward.vdb"),
               straight = readVolume(dir + "/straight.vdb");
  const float largest = largestMagnitude(baked.coefficients);
  EXPECT_GT(largestDifference(there.coefficients, baked.coefficients), 0.03f * largest) << "the other sky changed it";
  EXPECT_LT(largestDifference(onwards.coefficients, straight.coefficients), 1e-5f * largest);
  EXPECT_LT(largestDifference(onwards.skyDirect, straight.skyDirect), 1e-5f * largest);
}

void writeExr(const std::string& path, int width, int height, const std::vector<float>& rgb) {
  auto out = OIIO::ImageOutput::create(path);
  ASSERT_TRUE(out);
  const OIIO::ImageSpec spec(width, height, 3, OIIO::TypeDesc::FLOAT);
  ASSERT_TRUE(out->open(path, spec) && out->write_image(OIIO::TypeDesc::FLOAT, rgb.data()) && out->close());
}

// A smooth sky, brighter towards `towards` (the map's convention: u = ½ along +X, u = ¾ along +Z).
void writeGradientSky(const std::string& path, const Eigen::Vector3d& towards) {
  const int width = 128, height = 64;
  std::vector<float> rgb;
  for (int row = 0; row < height; ++row)
    for (int column = 0; column < width; ++column) {
      const double phi = 2.0 * M_PI * ((column + 0.5) / width - 0.5), theta = M_PI * (row + 0.5) / height;
      const Eigen::Vector3d d(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
      const float value = float(1.0 + d.dot(towards));
      for (const float tint : {1.0f, 0.8f, 0.6f}) rgb.push_back(value * tint);
    }
  writeExr(path, width, height, rgb);
}

double meanErrorOfLevel(const std::string& dir, const std::string& reference, const std::string& candidate) {
  const test::ProcessResult run = test::runBaker(dir, {"validate", reference, candidate, "--json"});
  EXPECT_NE(run.exitCode, 2) << run.err;
  return nlohmann::json::parse(run.out).at("error_of_level").at("mean").get<double>();
}

// default_room baked under sky `from` (flags), relit to sky `to`, against rebakes under `to` with
// seeds 1 and 7: the relit volume must be as close to the first as the second is.
void expectRelitWithinTheNoise(const std::string& dir, std::vector<std::string> from, std::vector<std::string> to) {
  const auto with = [](std::vector<std::string> sky, std::initializer_list<std::string> more) {
    sky.insert(sky.end(), more);
    return sky;
  };
  bake(dir, with(from, {"--rays", "256", "--out", "from.vdb"}));
  bake(dir, with(to, {"--rays", "256", "--out", "to.vdb"}));
  bake(dir, with(to, {"--rays", "256", "--seed", "7", "--out", "to7.vdb"}));
  std::vector<std::string> args = {"from.vdb", "--out", "relit.vdb"};
  args.insert(args.end(), to.begin(), to.end());
  ASSERT_EQ(relight(dir, args).exitCode, 0);
  const double relit = meanErrorOfLevel(dir, "to.vdb", "relit.vdb");
  const double noise = meanErrorOfLevel(dir, "to.vdb", "to7.vdb");
  EXPECT_LT(relit, 0.2);
  EXPECT_LT(relit, 1.2 * noise) << "noise " << noise;
}

// A white sky taken away and the low sun added (measured 0.12 of the level against a noise of
// 0.17): the constant sky's removal does not depend on how sharp V is.
TEST(Relight, MatchesARebakeWithinTheRebakesNoise) {
  expectRelitWithinTheNoise(test::makeTempDir("RelightRebake"), {"--sky", "1,1,1"}, {"--env", test::sourcePath(kLowSun)});
}

// The low sun taken away, a white sky added: the sun's sharp shadows went through the blurred
// visibility before sky_direct kept what the bake saw of it.
TEST(Relight, TakesASunAwayWithinTheRebakesNoise) {
  expectRelitWithinTheNoise(test::makeTempDir("RelightSunAway"), {"--env", test::sourcePath(kLowSun)}, {"--sky", "1,1,1"});
}

// A smooth sky taken away and another added: a sky bright towards +X, relit to one bright towards
// −X and up (measured 0.067 against a noise of 0.14).
TEST(Relight, SwapsSmoothSkiesWithinTheRebakesNoise) {
  const std::string dir = test::makeTempDir("RelightSmooth");
  writeGradientSky(dir + "/east.exr", {0.8, 0.0, 0.0});
  writeGradientSky(dir + "/west.exr", {-0.6, 0.3, 0.0});
  expectRelitWithinTheNoise(dir, {"--env", "east.exr"}, {"--env", "west.exr"});
}

TEST(Relight, RefusesWhatItCannotReadAndNeverWritesNaN) {
  const std::string dir = test::makeTempDir("RelightRefusals");
  bake(dir, {"--sky", "1,1,1", "--rays", "16", "--out", "baked.vdb"});
  const auto refused = [&](const std::vector<std::string>& args, const std::string& message) {
    const test::ProcessResult run = relight(dir, args);
    EXPECT_EQ(run.exitCode, 2) << run.err;
    EXPECT_NE(run.err.find(message), std::string::npos) << run.err;
    EXPECT_FALSE(std::filesystem::exists(dir + "/out.vdb"));
  };
  refused({"baked.vdb", "--out", "out.vdb"}, "--env is needed");
  const Volume old = test::smoothVolume({2, 2, 2}, {0, 0, 0}, 1.0);
  writeVdb(old, *makeBasis(old.basisName), dir + "/old.vdb");
  refused({"old.vdb", "--sky", "1,1,1", "--out", "out.vdb"}, "old.vdb: records no sky (baker.sky)");
  const test::ProcessResult runTime = test::runBaker(dir, {"validate", "baked.vdb", "old.vdb", "--run-time-sky", "1,1,1"});
  EXPECT_EQ(runTime.exitCode, 2);
  EXPECT_NE(runTime.err.find("old.vdb: holds no sky_direct grids"), std::string::npos) << runTime.err;
  bake(dir, {"--sky", "1,1,1", "--rays", "16", "--format", "bevy", "--out", "bevy"});
  refused({"bevy", "--sky", "1,1,1", "--out", "out.vdb"}, "holds no sky visibility");
  bake(dir, {"--sky", "1,1,1", "--rays", "16", "--non-negative", "--basis", "ad-srbf", "--out", "positive.vdb"});
  refused({"positive.vdb", "--sky", "2,2,2", "--out", "out.vdb"}, "was fitted with non-negative coefficients");
  const test::ProcessResult huge = relight(dir, {"baked.vdb", "--sky", "3e38,3e38,3e38", "--out", "out.vdb"});
  EXPECT_NE(huge.exitCode, 0);
  EXPECT_NE(huge.err.find("leave single precision"), std::string::npos) << huge.err;
  EXPECT_FALSE(std::filesystem::exists(dir + "/out.vdb"));

  // Texels that are not numbers are read as black, said once, and never reach the volume.
  std::vector<float> rgb(64 * 32 * 3, 1.0f);
  rgb[5] = std::numeric_limits<float>::quiet_NaN();
  rgb[99] = std::numeric_limits<float>::infinity();
  writeExr(dir + "/hostile.exr", 64, 32, rgb);
  const test::ProcessResult run = relight(dir, {"baked.vdb", "--env", "hostile.exr", "--out", "out.vdb"});
  ASSERT_EQ(run.exitCode, 0) << run.err;
  EXPECT_NE(run.err.find("2 texel(s) were negative or not finite and read as 0"), std::string::npos) << run.err;
  const Volume out = readVolume(dir + "/out.vdb");  // the reader refuses values that are not finite
  EXPECT_EQ(out.coefficients.size(), readVolume(dir + "/baked.vdb").coefficients.size());

  // A damaged sky is named.
  Volume v;
  std::vector<float> negative(128 * 64 * 3, 0.0f);
  negative[7] = -1.0f;
  const std::string negativeSky = nlohmann::json{{"width", 128}, {"height", 64}, {"radiance", negative}}.dump();
  const std::vector<std::string> damaged = {"{\"width\": 128}", "{\"width\": 128, \"height\": 64, \"radiance\": [1]}",
                                            "{\"width\": 64, \"height\": 32, \"radiance\": []}", "[]", negativeSky};
  for (const std::string& text : damaged) {
    try {
      readSky({{kSkyKey, text}}, v, "x.vdb");
      ADD_FAILURE() << text.substr(0, 80);
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("x.vdb: baker.sky"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace baker
