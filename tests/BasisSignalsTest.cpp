// `baker bases --signal … --metric …`: the metrics against values worked by hand, fits that
// reproduce what lies in a basis's span, non-negative fits that stay non-negative where linear
// ones ring, self-occlusion from a scene's suggested probes, and refused input.
#include <gtest/gtest.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "basis/BasisRegistry.h"
#include "common/Error.h"
#include "images/RgbImage.h"
#include "tests/BakerProcess.h"
#include "tests/TestData.h"
#include "validate/BasisEvaluation.h"

namespace baker {
namespace {

// A signal of kSignalWidth × kSignalWidth/2 texels: f(direction) in every channel, times `tint`.
template <typename F>
SphereSignal signalOf(const F& f, const Eigen::Vector3d& tint = Eigen::Vector3d::Ones(), bool scalar = false) {
  const int width = kSignalWidth, height = kSignalWidth / 2;
  const LatLongEnvironment layout(width, height, Eigen::MatrixX3d::Zero(width * height, 3));
  Eigen::MatrixX3d values(width * height, 3);
  for (int row = 0; row < height; ++row)
    for (int column = 0; column < width; ++column)
      values.row(row * width + column) = f(layout.direction(row, column)) * tint.transpose();
  return {"test", LatLongEnvironment(width, height, std::move(values)), scalar};
}

TEST(BasisSignals, RelativeErrorsAreTheThesisFormulas) {
  Eigen::MatrixX3d y(2, 3), x(2, 3);
  y << 1, 2, 3, 3, 2, 1;  // Σy = 12, mean 2
  x << 1, 1, 3, 3, 2, 4;  // |y − x| = 0 1 0 / 0 0 3: Σ = 4; Σ(y − x)² = 10
  EXPECT_DOUBLE_EQ(relativeMeanAbsoluteError(y, x, 3), 4.0 / 12.0);
  EXPECT_DOUBLE_EQ(relativeRootMeanSquareError(y, x, 3), std::sqrt(10.0 / 6.0) / 2.0);
  // One channel: only the first column counts (|1−1| + |3−3| = 0).
  EXPECT_DOUBLE_EQ(relativeMeanAbsoluteError(y, x, 1), 0.0);
}

// Constant images have no variance: SSIM is the luminance term (2μν + C1)/(μ² + ν² + C1) alone.
TEST(BasisSignals, SsimOfConstantImagesIsItsLuminanceTerm) {
  const Eigen::MatrixXd a = Eigen::MatrixXd::Constant(20, 20, 0.4), b = Eigen::MatrixXd::Constant(20, 20, 0.1);
  const double c1 = 0.01 * 0.01;
  EXPECT_NEAR(structuralSimilarity(a, b), (2 * 0.4 * 0.1 + c1) / (0.4 * 0.4 + 0.1 * 0.1 + c1), 1e-12);
  EXPECT_NEAR(structuralSimilarity(a, a), 1.0, 1e-12);
  // A structure the other image lacks costs similarity.
  Eigen::MatrixXd stripes = a;
  for (int r = 0; r < 20; r += 2) stripes.row(r).setConstant(0.8);
  EXPECT_LT(structuralSimilarity(a, stripes), 0.5);
}

// A signal in the span comes back exactly (the texels resolve every basis here), so every
// metric is at its best; a signal outside it does not.
TEST(BasisSignals, FitsReproduceTheirSpan) {
  const auto sh = makeBasis("sh-l2");
  const SphereSignal inSpan = signalOf([](const Eigen::Vector3d& d) { return 2.0 + d.x() - 0.5 * d.y() * d.z(); },
                                       Eigen::Vector3d(1.0, 0.5, 0.25));
  const FittedSignal fit(*sh, inSpan, FitMethod::Linear);
  EXPECT_LT(signalScore(inSpan, fit, SignalMetric::Rmae), 1e-6);
  EXPECT_LT(signalScore(inSpan, fit, SignalMetric::Rmse), 1e-6);
  EXPECT_GT(signalScore(inSpan, fit, SignalMetric::Ssim), 0.99999);
  const SphereSignal outside = signalOf([](const Eigen::Vector3d& d) { return 1.0 + std::pow(std::max(d.z(), 0.0), 20); });
  EXPECT_GT(signalScore(outside, FittedSignal(*sh, outside, FitMethod::Linear), SignalMetric::Rmae), 1e-3);
}

// A small bright source: the linear fits of non-negative functions ring below zero; the
// non-negative fits cannot.
TEST(BasisSignals, NonNegativeFitsStayNonNegativeWhereLinearOnesRing) {
  const SphereSignal spike = signalOf([](const Eigen::Vector3d& d) { return d.dot(Eigen::Vector3d(0.6, 0.48, 0.64)) > 0.995 ? 500.0 : 0.1; });
  for (const char* name : {"ad-srbf", "sg-12", "ad-linear"}) {
    const auto basis = makeBasis(name);
    ASSERT_TRUE(fitApplies(*basis, FitMethod::NonNegative)) << name;
    const double linearMin = FittedSignal(*basis, spike, FitMethod::Linear).atTexels(spike.image).minCoeff();
    const double constrainedMin = FittedSignal(*basis, spike, FitMethod::NonNegative).atTexels(spike.image).minCoeff();
    EXPECT_LT(linearMin, 0.0) << name;
    EXPECT_GE(constrainedMin, 0.0) << name;
  }
  EXPECT_FALSE(fitApplies(*makeBasis("sh-l2"), FitMethod::NonNegative));
}

TEST(BasisSignals, EvaluationListsEveryFitWithItsStatistics) {
  const std::vector<SphereSignal> signals = {
      signalOf([](const Eigen::Vector3d& d) { return 1.0 + 0.5 * d.y(); }),
      signalOf([](const Eigen::Vector3d& d) { return 1.0 + std::pow(std::max(d.x(), 0.0), 8); })};
  const std::vector<BasisScore> scores = evaluateBases({"sh-l1", "ad-srbf"}, signals, SignalMetric::Rmae);
  ASSERT_EQ(scores.size(), 3u);  // sh-l1 linear; ad-srbf linear and non-negative
  EXPECT_EQ(scores[0].bytesPerProbe, 4 * 12);
  EXPECT_EQ(scores[1].bytesPerProbe, 4 * 36);
  EXPECT_EQ(scores[2].fit, FitMethod::NonNegative);
  for (const BasisScore& s : scores) {
    ASSERT_EQ(s.perSignal.size(), 2u);
    EXPECT_DOUBLE_EQ(s.mean, 0.5 * (s.perSignal[0] + s.perSignal[1]));
    EXPECT_NEAR(s.standardDeviation, std::abs(s.perSignal[0] - s.perSignal[1]) / std::sqrt(2.0), 1e-15);
  }
  EXPECT_LT(scores[0].perSignal[0], 1e-6);  // 1 + 0.5·y lies in SH band 1 (coefficients are floats)
}

TEST(BasisSignals, DownsamplingKeepsTheIntegral) {
  Eigen::MatrixX3d radiance(512 * 256, 3);
  for (int t = 0; t < radiance.rows(); ++t) radiance.row(t).setConstant(double((t * 7919) % 101));
  const LatLongEnvironment full(512, 256, radiance);
  const LatLongEnvironment small = areaDownsampled(full, kSignalWidth, "full.exr");
  auto integral = [](const LatLongEnvironment& e) {
    const DirectionSet texels = e.texels();
    double sum = 0.0;
    for (std::size_t t = 0; t < texels.size(); ++t) sum += texels.weights[t] * e.radiance()(std::int64_t(t), 0);
    return sum;
  };
  EXPECT_NEAR(integral(small), integral(full), 1e-9 * integral(full));
  EXPECT_THROW(areaDownsampled(LatLongEnvironment(200, 100, Eigen::MatrixX3d::Ones(20000, 3)), kSignalWidth, "odd.exr"),
               InputError);
}

// The sunlit yard suggests three probes; those partly open to the sky give binary signals.
TEST(BasisSignals, OcclusionComesFromTheScenesSuggestedProbes) {
  std::vector<std::string> skipped;
  const std::vector<SphereSignal> signals =
      occlusionSignals(test::sourcePath("data/sunlit_yard/sunlit_yard.gltf"), skipped);
  ASSERT_EQ(signals.size() + skipped.size(), 3u);
  ASSERT_FALSE(signals.empty());
  for (const SphereSignal& s : signals) {
    EXPECT_TRUE(s.scalar);
    const Eigen::VectorXd open = s.image.radiance().col(0);
    EXPECT_TRUE((open.array() == 0.0 || open.array() == 1.0).all()) << s.name;
    // Every probe stands above the yard's ground under open sky: the top row of texels (around
    // +Y) is open and the bottom row (around −Y) meets the ground. A flipped or turned ray would
    // not give both.
    const int width = s.image.width(), height = s.image.height();
    EXPECT_EQ(open.head(width).sum(), double(width)) << s.name;
    EXPECT_EQ(open.segment(std::int64_t(height - 1) * width, width).sum(), 0.0) << s.name;
  }
}

TEST(BasisSignals, CommandReportsJsonAndRefusesBadInput) {
  const std::string dir = test::makeTempDir("BasisSignalsCommand");
  RgbImage image(256, 128);
  for (int row = 0; row < 128; ++row)
    for (int column = 0; column < 256; ++column)
      std::fill_n(image.pixel(row, column), 3, row < 40 ? 2.0f : 0.25f);
  writeExr(image, dir + "/sky.exr");
  const test::ProcessResult run = test::runBaker(dir, "bases --signal irradiance --metric ssim --basis sh-l2 "
                                                      "--basis sg-12 sky.exr --json");
  ASSERT_EQ(run.exitCode, 0) << run.err;
  const nlohmann::json report = nlohmann::json::parse(run.out);
  EXPECT_EQ(report.at("signal"), "irradiance");
  EXPECT_EQ(report.at("metric"), "ssim");
  EXPECT_TRUE(report.at("higher_is_better").get<bool>());
  ASSERT_EQ(report.at("scores").size(), 3u);  // sh-l2; sg-12 linear and non-negative
  for (const auto& score : report.at("scores")) {
    EXPECT_GT(score.at("mean").get<double>(), 0.9) << score.dump();
    EXPECT_LE(score.at("mean").get<double>(), 1.0) << score.dump();
  }

  auto refused = [&](const std::string& args, const std::string& needle) {
    const test::ProcessResult bad = test::runBaker(dir, args);
    EXPECT_EQ(bad.exitCode, 2) << args;
    EXPECT_NE(bad.err.find(needle), std::string::npos) << bad.err;
  };
  refused("bases --signal light sky.exr", "light");
  refused("bases --signal radiance --metric psnr sky.exr", "psnr");
  refused("bases --signal radiance", "light probes");
  refused("bases --signal radiance missing.hdr", "missing.hdr");
  refused("bases --signal radiance --basis sh-l99 sky.exr", "sh-l99");
  refused("bases --metric rmae", "--signal");
  std::ofstream(dir + "/bare.gltf") << R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[]}]})";
  refused("bases --signal occlusion bare.gltf", "bare.gltf: the scene suggests no probe position");
  std::ofstream(dir + "/open.gltf")
      << R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[],"extras":{"probe_hint":[[0,0,0]]}}]})";
  refused("bases --signal occlusion open.gltf", "partly occluded");
  std::ofstream(dir + "/odd.gltf")
      << R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[],"extras":{"probe_hint":[[0,"up",0]]}}]})";
  refused("bases --signal occlusion odd.gltf", "scenes[0].extras.probe_hint[0] is not a finite");
  RgbImage black(256, 128);
  writeExr(black, dir + "/black.exr");
  refused("bases --signal radiance black.exr", "black.exr: every texel is black");
}

}  // namespace
}  // namespace baker
