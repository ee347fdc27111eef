#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <random>
#include <string>
#include <vector>

#include "basis/BasisRegistry.h"
#include "common/Error.h"
#include "images/RgbImage.h"
#include "tests/BakerProcess.h"
#include "tests/TestData.h"
#include "validate/IrradianceFit.h"
#include "validate/IrradianceReference.h"
#include "validate/LatLongEnvironment.h"

namespace baker {
namespace {

// Writes a float RGB OpenEXR straight through OpenImageIO, independently of the code under test.
void writeTestImage(const std::string& path, int width, int height, const std::vector<float>& rgb) {
  auto out = OIIO::ImageOutput::create(path);
  ASSERT_TRUE(out) << OIIO::geterror();
  const OIIO::ImageSpec spec(width, height, 3, OIIO::TypeDesc::FLOAT);
  ASSERT_TRUE(out->open(path, spec) && out->write_image(OIIO::TypeDesc::FLOAT, rgb.data()) && out->close())
      << out->geterror();
}

std::vector<float> randomRadiance(int width, int height, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> uniform(0.0f, 4.0f);
  std::vector<float> rgb(std::size_t(width) * height * 3);
  for (float& v : rgb) v = uniform(rng);
  return rgb;
}

TEST(LatLongEnvironment, DirectionsFollowTheLightProbeConvention) {
  const LatLongEnvironment env(4, 2, Eigen::MatrixX3d::Zero(8, 3));
  // Texel (row 0, column 0): u = 1/8, v = 1/4, so θ = −3π/4 and φ = π/4.
  EXPECT_LT((env.direction(0, 0) - Eigen::Vector3d(-0.5, std::sqrt(0.5), 0.5)).norm(), 1e-15);
  // Texel (row 1, column 2): θ = π/4, φ = 3π/4: below the horizon, towards +X and −Z.
  EXPECT_LT((env.direction(1, 2) - Eigen::Vector3d(0.5, -std::sqrt(0.5), -0.5)).norm(), 1e-15);
  // Rows are the bands between latitudes 90°, 0° and −90°: 2π each, 4 texels per row.
  EXPECT_NEAR(env.texelSolidAngle(0), M_PI / 2, 1e-15);
  EXPECT_NEAR(env.texelSolidAngle(1), M_PI / 2, 1e-15);
}

TEST(LatLongEnvironment, TexelSolidAnglesTileTheSphere) {
  const LatLongEnvironment env(256, 128, Eigen::MatrixX3d::Zero(256 * 128, 3));
  const DirectionSet texels = env.texels();
  double total = 0.0;
  for (double w : texels.weights) total += w;
  EXPECT_NEAR(total, 4 * M_PI, 1e-12);
  for (const Eigen::Vector3d& d : texels.directions) ASSERT_NEAR(d.norm(), 1.0, 1e-15);
}

TEST(ExactIrradiance, FastSumEqualsTheDirectTexelSum) {
  const int width = 32, height = 16;
  const std::vector<float> rgb = randomRadiance(width, height, 3);
  Eigen::MatrixX3d radiance(width * height, 3);
  for (int t = 0; t < width * height; ++t)
    for (int c = 0; c < 3; ++c) radiance(t, c) = rgb[3 * t + c];
  const LatLongEnvironment env(width, height, radiance);
  const Eigen::MatrixX3d fast = exactIrradiance(env);

  const DirectionSet texels = env.texels();
  for (std::size_t n = 0; n < texels.size(); ++n) {
    Eigen::Vector3d direct = Eigen::Vector3d::Zero();
    for (std::size_t t = 0; t < texels.size(); ++t)
      direct += std::max(0.0, texels.directions[n].dot(texels.directions[t])) * texels.weights[t] *
                radiance.row(t).transpose();
    ASSERT_LT((fast.row(n).transpose() - direct).norm(), 1e-13 * direct.norm()) << "texel " << n;
  }
}

// A constant environment L has irradiance πL everywhere. The texel sum is a quadrature of the
// clamped cosine, exact in the band areas but not across the horizon, which cuts texels: at
// 256 × 128 it is within 3.1e-5 of π (measured; it shrinks as the texel size squared).
TEST(ExactIrradiance, ConstantEnvironmentGivesPiTimesTheRadiance) {
  const std::string dir = test::makeTempDir("constant-environment");
  const int width = 256, height = 128;
  const Eigen::Vector3f radiance(0.5f, 1.0f, 2.0f);
  std::vector<float> rgb(std::size_t(width) * height * 3);
  for (std::size_t t = 0; t < rgb.size() / 3; ++t)
    for (int c = 0; c < 3; ++c) rgb[3 * t + c] = radiance[c];
  writeTestImage(dir + "/constant.exr", width, height, rgb);

  const LatLongEnvironment env = LatLongEnvironment::load(dir + "/constant.exr");
  const Eigen::MatrixX3d irradiance = exactIrradiance(env);
  double worst = 0.0;
  for (int t = 0; t < env.texelCount(); ++t)
    for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(irradiance(t, c) / (M_PI * radiance[c]) - 1.0));
  EXPECT_LT(worst, 4e-5);
  // At the top row's texel directions the horizon falls on texel centres of the two equator
  // rows, where the cosine is 0 anyway, and the sum is exact.
  for (int column = 0; column < width; ++column)
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(irradiance(column, c) / (M_PI * radiance[c]), 1.0, 1e-12);
  std::filesystem::remove_all(dir);
}

TEST(LatLongEnvironment, RejectsMissingUnreadableAndInvalidFilesNamingThem) {
  const std::string dir = test::makeTempDir("bad-environments");
  const auto expectRejected = [](const std::string& path, const std::string& needle) {
    try {
      LatLongEnvironment::load(path);
      ADD_FAILURE() << path << " must be rejected";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
    }
  };
  expectRejected(dir + "/missing.hdr", "no such file");
  std::ofstream(dir + "/text.hdr") << "not an image\n";
  expectRejected(dir + "/text.hdr", "cannot read");
  std::vector<float> rgb(8 * 4 * 3, 1.0f);
  rgb[3 * 9 + 1] = -0.25f;
  writeTestImage(dir + "/negative.exr", 8, 4, rgb);
  expectRejected(dir + "/negative.exr", "channel G is -0.25");
  rgb[3 * 9 + 1] = std::nanf("");
  writeTestImage(dir + "/nan.exr", 8, 4, rgb);
  expectRejected(dir + "/nan.exr", "(column 1, row 1) channel G is nan");
  std::filesystem::remove_all(dir);
}

// The irradiance RMSE (on E/π) of the paper's SH rows against the exact texel sum, from
// ../shared/notes/ambient-dice-definitions.md. Its one L4 value serves both: that irradiance is
// nowhere negative on these probes, so clamping changes nothing.
struct ShExpectation {
  const char* probe;
  int order;
  double unclamped, clamped;
};

TEST(ShIrradianceOnProbes, MatchTheVerifiedTableWithinOnePercent) {
  REQUIRE_SHARED_DATA();
  const ShExpectation expectations[] = {
      {"ennis", 1, 0.5585, 0.5069}, {"ennis", 2, 0.09517, 0.09414}, {"ennis", 4, 0.02985, 0.02985},
      {"grace", 1, 0.08946, 0.08222}, {"grace", 2, 0.01300, 0.01300}, {"grace", 4, 0.005405, 0.005405},
  };
  std::string loaded;
  std::unique_ptr<LatLongEnvironment> env;
  Eigen::MatrixX3d reference;
  for (const ShExpectation& e : expectations) {
    if (loaded != e.probe) {
      env = std::make_unique<LatLongEnvironment>(
          LatLongEnvironment::load(test::sharedDataPath(std::string("probes/") + e.probe + ".hdr")));
      reference = exactIrradiance(*env);
      loaded = e.probe;
    }
    const auto basis = makeBasis("sh-l" + std::to_string(e.order));
    const std::vector<IrradianceFit> fits = fitIrradiance(*basis, *env, reference);
    ASSERT_EQ(fits.size(), 2u);
    EXPECT_EQ(fits[0].method, "unclamped");
    EXPECT_EQ(fits[1].method, "clamped");
    EXPECT_NEAR(fits[0].rmse, e.unclamped, 0.01 * e.unclamped) << e.probe << " sh-l" << e.order << " unclamped";
    EXPECT_NEAR(fits[1].rmse, e.clamped, 0.01 * e.clamped) << e.probe << " sh-l" << e.order << " clamped";
  }
}

// The notes' exact-reference values for the Ambient Dice fits (solid-angle-weighted least
// squares to the exact irradiance image), within 1 %.
TEST(AmbientDiceIrradianceOnProbes, MatchTheVerifiedTableWithinOnePercent) {
  REQUIRE_SHARED_DATA();
  struct Expectation {
    const char* basis;
    double ennis, grace;
  };
  const Expectation expectations[] = {{"ad-rgb", 0.03935, 0.007631}, {"ad-rgb-flat", 0.03767, 0.006011},
                                      {"ad-srbf", 0.09891, 0.01401}};
  for (const char* probe : {"ennis", "grace"}) {
    const LatLongEnvironment env =
        LatLongEnvironment::load(test::sharedDataPath(std::string("probes/") + probe + ".hdr"));
    const Eigen::MatrixX3d reference = exactIrradiance(env);
    for (const Expectation& e : expectations) {
      const std::vector<IrradianceFit> fits = fitIrradiance(*makeBasis(e.basis), env, reference);
      ASSERT_EQ(fits[0].method, "weighted_fit");
      const double expected = std::string(probe) == "ennis" ? e.ennis : e.grace;
      EXPECT_NEAR(fits[0].rmse, expected, 0.01 * expected) << probe << " " << e.basis;
    }
  }
}

// A 60-byte Radiance header may claim 20000 × 20000 texels; the reader must refuse it before
// allocating the 4.8 GB it implies.
TEST(RgbImage, RefusesAClaimedSizeBeyondTheLimitBeforeReading) {
  const std::string path = test::makeTempDir("huge-hdr") + "/huge.hdr";
  std::ofstream(path, std::ios::binary) << "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 20000 +X 20000\n\x02\x02N ";
  try {
    readRgbImage(path);
    FAIL() << "a 20000 × 20000 image must be refused";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("exceed the limit"), std::string::npos) << e.what();
  }
}

// Runs `baker env ARGS...` in `dir`, as a user would.
test::ProcessResult runEnv(const std::string& dir, std::vector<std::string> args) {
  args.insert(args.begin(), "env");
  return test::runBaker(dir, args);
}

std::vector<std::string> filesIn(const std::string& dir) {
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

class EnvCommand : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = test::makeTempDir(std::string("env-") + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    probe_ = dir_ + "/probe.exr";
    writeTestImage(probe_, 32, 16, randomRadiance(32, 16, 11));
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  // Exit code 2, one line on stderr mentioning `needle`, and nothing written beside the probe.
  void expectRejected(const std::vector<std::string>& args, const std::string& needle) {
    const test::ProcessResult run = runEnv(dir_, args);
    EXPECT_EQ(run.exitCode, 2) << run.err;
    EXPECT_NE(run.err.find(needle), std::string::npos) << run.err;
    EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
    EXPECT_EQ(filesIn(dir_), std::vector<std::string>{"probe.exr"});
  }
  std::string dir_, probe_;
};

TEST_F(EnvCommand, MissingProbeIsRejected) {
  expectRejected({dir_ + "/missing.hdr", "--basis", "sh-l2", "--out-dir", dir_}, "missing.hdr");
}

TEST_F(EnvCommand, UnknownBasisIsRejected) { expectRejected({probe_, "--basis", "sh-l99", "--out-dir", dir_}, "sh-l99"); }

TEST_F(EnvCommand, SgSharpnessIsRejectedForOtherBases) {
  expectRejected({probe_, "--basis", "sh-l2", "--sg-sharpness", "4", "--out-dir", dir_}, "--sg-sharpness");
}

TEST_F(EnvCommand, ReportsBothFitsAsJsonAndWritesTheImages) {
  const test::ProcessResult run = runEnv(dir_, {probe_, "--basis", "ambient-cube", "--json", "--out-dir", dir_});
  ASSERT_EQ(run.exitCode, 0) << run.err;
  const nlohmann::json report = nlohmann::json::parse(run.out);
  EXPECT_EQ(report.at("basis"), "ambient-cube");
  EXPECT_EQ(report.at("coefficients"), 18);
  EXPECT_EQ(report.at("coefficients_per_lookup"), 9);
  const double weighted = report.at("rmse").at("weighted_fit"), unweighted = report.at("rmse").at("unweighted_fit");
  EXPECT_GT(weighted, 0.0);
  EXPECT_GT(unweighted, 0.0);
  EXPECT_EQ(filesIn(dir_), (std::vector<std::string>{"error.exr", "error.png", "probe.exr", "reconstruction.exr",
                                                      "reconstruction.png", "reference.exr", "reference.png"}));

  // reference.exr holds E/π of the exact sum.
  const Eigen::MatrixX3d reference = exactIrradiance(LatLongEnvironment::load(probe_));
  auto in = OIIO::ImageInput::open(dir_ + "/reference.exr");
  ASSERT_TRUE(in) << OIIO::geterror();
  std::vector<float> pixels(32 * 16 * 3);
  ASSERT_TRUE(in->read_image(0, 0, 0, 3, OIIO::TypeDesc::FLOAT, pixels.data()));
  for (int t = 0; t < 32 * 16; ++t)
    for (int c = 0; c < 3; ++c) ASSERT_NEAR(pixels[3 * t + c], reference(t, c) / M_PI, 1e-6 * reference(t, c));
}

}  // namespace
}  // namespace baker
