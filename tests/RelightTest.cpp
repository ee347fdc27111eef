// Relighting (relight/Relighting.h, volume/SkyTransfer.h): a probe under open sky against the
// sky's irradiance summed here from the map's own texels, the same sky giving the bake back bit for
// bit, a round trip through another sky, a relit volume against a rebake under the new sky within
// the rebake's own noise, and the inputs it refuses.
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

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

void bake(const std::string& dir, std::vector<std::string> args) {
  args.insert(args.begin(), test::sourcePath("data/default_room/default_room.gltf"));
  for (const char* a : {"--bounces", "0", "--spacing", "1", "--quiet"}) args.push_back(a);
  const test::ProcessResult run = test::runBaker(dir, args);
  ASSERT_EQ(run.exitCode, 0) << run.err;
}

test::ProcessResult relight(const std::string& dir, std::vector<std::string> args) {
  args.insert(args.begin(), "relight");
  return test::runBaker(dir, args);
}

TEST(Relight, TheSameSkyGivesTheBakeBackAndARoundTripReturns) {
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

  ASSERT_EQ(relight(dir, {"baked.vdb", "--sky", "0.3,0.4,0.5", "--out", "there.vdb"}).exitCode, 0);
  const test::ProcessResult back = relight(dir, {"there.vdb", "--env", sky, "--out", "back.vdb", "--json"});
  ASSERT_EQ(back.exitCode, 0) << back.err;
  const nlohmann::json report = nlohmann::json::parse(back.out);
  EXPECT_EQ(report.at("from_sky"), "constant 0.3,0.4,0.5");
  EXPECT_EQ(report.at("baked_sky"), baked.settings.at("sky"));
  EXPECT_EQ(report.at("keeps").size(), 1u) << "the emissive panel's light";
  const Volume there = readVolume(dir + "/there.vdb"), returned = readVolume(dir + "/back.vdb");
  float largest = 0.0f, moved = 0.0f, off = 0.0f;
  for (std::size_t i = 0; i < baked.coefficients.size(); ++i) {
    largest = std::max(largest, std::abs(baked.coefficients[i]));
    moved = std::max(moved, std::abs(there.coefficients[i] - baked.coefficients[i]));
    off = std::max(off, std::abs(returned.coefficients[i] - baked.coefficients[i]));
  }
  EXPECT_GT(moved, 0.03f * largest) << "the other sky changed the volume";
  EXPECT_LT(off, 1e-5f * largest) << "and coming back undoes it to float rounding";
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
