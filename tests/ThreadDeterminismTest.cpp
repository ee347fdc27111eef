#include <gtest/gtest.h>
#include "bake/Baker.h"
#include "basis/BasisRegistry.h"
#include "scene/GltfLoader.h"
#include "scene/RayTracer.h"
#include "tests/OnThreads.h"
#include "tests/TestData.h"

namespace baker {
namespace {

// Bricks are shared out between threads, and within a brick the probes' placement and tracing
// are too: every number of threads must give the same bits and the same ray counts. default_room
// with a point light and a sky map added has every effect a bake simulates: bounces, an
// emissive panel, a punctual light seen by the probes and by every bounce, a sky with a bright
// spot through the open side, probes in walls, and every kind of direct-view sample and aim;
// with a fixed lattice, with adaptive rounds, where probes stop at different rounds, and with a
// fixed lattice whose probes share their reflections, summed in the order of the probes.
enum class Lattice { Fixed, Adaptive, Shared };
class ThreadDeterminism : public ::testing::TestWithParam<Lattice> {};

TEST_P(ThreadDeterminism, EveryThreadCountBakesTheSameVolume) {
  const bool adaptive = GetParam() == Lattice::Adaptive;
  Scene scene = loadGltf(test::sourcePath("data/default_room/default_room.gltf"));
  PunctualLight lamp;
  lamp.position = scene.bounds.center();
  lamp.intensity = 5.0f;
  scene.lights.push_back(lamp);
  std::vector<float> sky(16 * 8 * 3, 0.2f);
  for (int c = 0; c < 3; ++c) sky[(3 * 16 + 12) * 3 + c] = 200.0f;
  scene.environment = Environment::latLong(16, 8, sky, 1.0f, 0.0f, "spot sky");
  const RayTracer tracer(scene);
  const auto basis = makeBasis("ad-ycocg");
  const ProbeGrid grid = makeProbeGrid(scene.bounds, 0.4, 100000);
  BakeSettings settings;
  settings.rays = 64;
  if (adaptive) {  // rounds of 2 × 16, 32, 64 directions: at most 224 per probe
    settings.rays = 16;
    settings.convergence = {0.05, 1, 3};
  }
  if (GetParam() == Lattice::Shared) settings.sharedReflectionCell = 0.2f;
  const auto bakeWith = [&](int threads, BakeStats* stats) {
    return test::onThreads(threads, [&] { return bakeVolume(scene, tracer, *basis, grid, settings, stats); });
  };
  BakeStats oneStats;
  const Volume one = bakeWith(1, &oneStats);
  ASSERT_GT(oneStats.bricks, 1);
  ASSERT_GT(oneStats.relocatedProbes + oneStats.invalidProbes, 0) << "no probe exercises the placement";
  ASSERT_GT(oneStats.rays.directPunctualShadow, 0) << "no probe sees the point light";
  ASSERT_GT(oneStats.rays.punctualShadow, 0) << "no bounce sees the point light";
  ASSERT_GT(oneStats.rays.environmentShadow, 0) << "no bounce samples the sky";
  ASSERT_GT(oneStats.rays.directView, 0) << "no direct-view samples";
  ASSERT_GT(oneStats.rays.directViewShadow, 0) << "no aim near the light found a lit surface";
  ASSERT_GT(oneStats.rays.aimedBounce, 0) << "no path vertex aimed at the light";
  if (adaptive) {
    ASSERT_GT(oneStats.lattice.atLimit, 0) << "no probe took every round";
    ASSERT_LT(oneStats.lattice.atLimit, oneStats.lattice.probes) << "no probe stopped early";
  }
  for (int threads : {2, 3}) {
    BakeStats stats;
    const Volume other = bakeWith(threads, &stats);
    EXPECT_EQ(other.coefficients, one.coefficients) << threads << " threads";
    EXPECT_EQ(other.visibility, one.visibility) << threads << " threads";
    EXPECT_EQ(other.skyDirect, one.skyDirect) << threads << " threads";
    EXPECT_EQ(other.skyBounced, one.skyBounced) << threads << " threads";
    EXPECT_EQ(other.states, one.states) << threads << " threads";
    ASSERT_EQ(other.offsets.size(), one.offsets.size());
    for (std::size_t p = 0; p < one.offsets.size(); ++p)
      ASSERT_EQ(other.offsets[p], one.offsets[p]) << "probe " << p << ", " << threads << " threads";
    EXPECT_EQ(stats.rays.total(), oneStats.rays.total()) << threads << " threads";
    EXPECT_EQ(stats.rays.validity, oneStats.rays.validity) << threads << " threads";
    EXPECT_EQ(stats.rays.bounce, oneStats.rays.bounce) << threads << " threads";
    EXPECT_EQ(stats.rays.directPunctualShadow, oneStats.rays.directPunctualShadow) << threads << " threads";
    EXPECT_EQ(stats.rays.directView, oneStats.rays.directView) << threads << " threads";
    EXPECT_EQ(stats.rays.aimedBounceShadow, oneStats.rays.aimedBounceShadow) << threads << " threads";
    EXPECT_EQ(stats.lattice.rays, oneStats.lattice.rays) << threads << " threads";
  }
}

INSTANTIATE_TEST_SUITE_P(Lattices, ThreadDeterminism, ::testing::Values(Lattice::Fixed, Lattice::Adaptive, Lattice::Shared),
                         [](const ::testing::TestParamInfo<Lattice>& info) {
                           return info.param == Lattice::Fixed ? "fixed" : info.param == Lattice::Adaptive ? "adaptive" : "shared";
                         });

}  // namespace
}  // namespace baker
