#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "bake/ProbeBaker.h"
#include "bake/ProbeConvergence.h"
#include "bake/TransportPlan.h"
#include "basis/ShBasis.h"
#include "formats/VolumeSampler.h"
#include "scene/GltfLoader.h"
#include "scene/RayTracer.h"
#include "scene/SceneCensus.h"
#include "tests/SeedStatistics.h"
#include "tests/TestData.h"

namespace baker {
namespace {

using Axes = RoundStatistics::AxisIrradiance;

TEST(ProbeConvergence, RaysDoubleEveryRound) {
  EXPECT_EQ(raysAfterRounds(256, 0), 0);
  EXPECT_EQ(raysAfterRounds(256, 1), 512);
  EXPECT_EQ(raysAfterRounds(256, 2), 1536);
  EXPECT_EQ(raysAfterRounds(256, 9), 261632);
  EXPECT_EQ(raysAfterRounds(256, 11), 1048064);
}

// Two rounds of n = 100 and 200 rays per lattice: the mean weighs every ray alike, and
// Var(mean) = Σ n_t² (a_t − b_t)² / N², N = 600.
TEST(ProbeConvergence, MeanAndStandardErrorOfRounds) {
  RoundStatistics s(Axes::Zero());
  EXPECT_TRUE(std::isinf(s.relativeStandardError()));
  s.add(100, Axes::Constant(1.0), Axes::Constant(3.0));
  EXPECT_NEAR(s.mean()(0, 0), 2.0, 1e-12);
  // S = |E| + ½·mean over axes = 2 + 1 = 3; standard error = 100·2/200 = 1.
  EXPECT_NEAR(s.relativeStandardError(), 1.0 / 3.0, 1e-12);
  s.add(200, Axes::Constant(2.0), Axes::Constant(2.5));
  const double mean = (100.0 * 4.0 + 200.0 * 4.5) / 600.0;
  EXPECT_NEAR(s.mean()(3, 2), mean, 1e-12);
  const double standardError = std::sqrt(100.0 * 100.0 * 4.0 + 200.0 * 200.0 * 0.25) / 600.0;
  EXPECT_NEAR(s.relativeStandardError(), standardError / (1.5 * mean), 1e-12);
}

// The fixed part (punctual lights seen directly) counts in S, and a black channel waits for nothing.
TEST(ProbeConvergence, FixedLightCountsInTheScaleAndBlackChannelsAreConverged) {
  Axes fixed = Axes::Zero();
  fixed.col(0).setConstant(8.0);
  RoundStatistics s(fixed);
  Axes a = Axes::Zero(), b = Axes::Zero();
  a.col(0).setConstant(1.0);
  b.col(0).setConstant(3.0);
  s.add(10, a, b);
  EXPECT_NEAR(s.relativeStandardError(), 1.0 / (10.0 + 5.0), 1e-12);
}

TEST(ProbeConvergence, StopsAfterTwoRoundsInARowUnderTheTarget) {
  const ConvergenceSettings settings{0.01, 2, 9};
  RoundStatistics s(Axes::Zero());
  s.add(256, Axes::Constant(1.0), Axes::Constant(1.0001));
  EXPECT_FALSE(s.converged(settings)) << "fewer than minRounds";
  s.add(512, Axes::Constant(1.0), Axes::Constant(1.05));  // 1.1 % of S
  EXPECT_FALSE(s.converged(settings)) << "over the target";
  s.add(1024, Axes::Constant(1.0), Axes::Constant(1.0));
  EXPECT_FALSE(s.converged(settings)) << "under the target once only";
  s.add(2048, Axes::Constant(1.0), Axes::Constant(1.0));
  EXPECT_TRUE(s.converged(settings));
}

// A uniform sky of radiance 1 and nothing else: E(n) = π for every normal, and every lattice
// agrees with every other up to its quadrature, so the probe stops as early as it may (two
// rounds, 1536 rays) and the result is π.
TEST(ProbeConvergence, UniformSkyStopsAtTheFewestRounds) {
  Scene scene;
  scene.environment = Environment::constant(Eigen::Vector3f::Ones());
  const RayTracer tracer(scene);
  std::vector<PlannedEffect> plan = planEffects(scene, takeCensus(scene));
  BakeSettings settings;
  const QualityPreset& preset = *findQualityPreset("default");
  settings.rays = preset.rays;
  settings.convergence = preset.convergence;
  settings.transport = transportSettings(plan, 3, 0);
  const ShBasis basis(2);
  const ProbeBaker baker(scene, tracer, basis, settings, 1);
  const std::vector<ProbeTask> tasks = {{Eigen::Vector3f::Zero(), 0, 0}};
  std::vector<float> coefficients(baker.coefficientsPerProbe()), visibility(baker.visibilityPerProbe());
  std::vector<ProbeSamples> samples;
  RayCounts counts;
  RoundTally tally;
  baker.bake(tasks, coefficients.data(), visibility.data(), &counts, &samples, &tally);
  EXPECT_EQ(tally.rays, 1536);
  EXPECT_EQ(tally.atLimit, 0);
  EXPECT_EQ(counts.probe, 1536);
  for (const Eigen::Vector3f n : {Eigen::Vector3f(1, 0, 0), Eigen::Vector3f(0, -1, 0), Eigen::Vector3f(0, 0, 1)}) {
    EXPECT_NEAR(sampledIrradiance(samples[0], n).x(), M_PI, 1e-3 * M_PI);
    EXPECT_NEAR(basis.reconstruct(coefficients.data(), n.cast<double>()).x(), M_PI, 1e-3 * M_PI);
    EXPECT_NEAR(reconstructVisibility(basis, visibility.data(), n.cast<double>()), 1.0, 1e-3);
  }
}

// The stopping rule's own error estimate against one it does not use: the spread of
// independent seeds. At quality draft (5 %), the seeds' spread of single bakes of default_room's
// probes, lit by its emissive panel through bounces, stays near 5 % of S on every axis and
// channel (at most 1.6×, for the noise of eight seeds' spread), while the probes' ray counts
// differ.
TEST(ProbeConvergence, SeedSpreadMatchesTheTargetError) {
  const Scene scene = loadGltf(test::sourcePath("data/default_room/default_room.gltf"));
  const RayTracer tracer(scene);
  std::vector<PlannedEffect> plan = planEffects(scene, takeCensus(scene));
  const ShBasis basis(2);
  const std::vector<Eigen::Vector3f> probes = {scene.bounds.center(),
                                               scene.bounds.min() + 0.2f * scene.bounds.sizes()};
  const QualityPreset& preset = *findQualityPreset("draft");
  std::vector<std::vector<double>> values(probes.size() * 18);
  std::vector<std::int64_t> rays;
  for (std::uint64_t seed = 1; seed <= 8; ++seed) {
    BakeSettings settings;
    settings.rays = preset.rays;
    settings.convergence = preset.convergence;
    settings.transport = transportSettings(plan, 3, seed);
    const ProbeBaker baker(scene, tracer, basis, settings, 1);
    for (std::size_t p = 0; p < probes.size(); ++p) {
      std::vector<float> coefficients(baker.coefficientsPerProbe()), visibility(baker.visibilityPerProbe());
      std::vector<ProbeSamples> samples;
      RayCounts counts;
      RoundTally tally;
      baker.bake({{probes[p], std::uint64_t(p), 0}}, coefficients.data(), visibility.data(), &counts, &samples,
                 &tally);
      rays.push_back(tally.rays);
      const Eigen::Vector3f axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
      for (int a = 0; a < 6; ++a) {
        const Eigen::Vector3f e = sampledIrradiance(samples[0], axes[a]);
        for (int c = 0; c < 3; ++c) values[p * 18 + a * 3 + c].push_back(e[c]);
      }
    }
  }
  for (std::size_t p = 0; p < probes.size(); ++p)
    for (int c = 0; c < 3; ++c) {
      double mean = 0.0;
      for (int a = 0; a < 6; ++a) mean += test::overSeeds(values[p * 18 + a * 3 + c]).mean / 6.0;
      for (int a = 0; a < 6; ++a) {
        const test::SeedStatistics s = test::overSeeds(values[p * 18 + a * 3 + c]);
        const double scale = std::abs(s.mean) + 0.5 * mean;
        const double spread = s.standardError * std::sqrt(8.0);  // of one bake
        EXPECT_LE(spread, 1.6 * preset.convergence.targetError * scale)
            << "probe " << p << " axis " << a << " channel " << c << ": spread " << spread / scale << " of S";
      }
    }
  EXPECT_NE(*std::min_element(rays.begin(), rays.end()), *std::max_element(rays.begin(), rays.end()))
      << "every bake took the same rays: nothing adapted";
}

}  // namespace
}  // namespace baker
