// Probes that share what their paths bring back from surfaces (bake/SharedReflections.h): the
// same light as each probe's own paths where the light does not vary across a cell, and less noise.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "bake/ProbesAt.h"
#include "basis/ShBasis.h"
#include "scene/GltfLoader.h"
#include "scene/RayTracer.h"
#include "tests/TestData.h"

namespace baker {
namespace {

const Eigen::Vector3f kAxes[3] = {{1, 0, 0}, {0, -1, 0}, {0, 0, 1}};

// A 3 × 3 × 3 block of probes `step` apart about `centre`, rotation 0, ids 0, 1, ...
std::vector<ProbeTask> block(const Eigen::Vector3f& centre, float step) {
  std::vector<ProbeTask> tasks;
  for (int k = -1; k <= 1; ++k)
    for (int j = -1; j <= 1; ++j)
      for (int i = -1; i <= 1; ++i)
        tasks.push_back({centre + step * Eigen::Vector3f(float(i), float(j), float(k)), std::uint64_t(tasks.size()), 0});
  return tasks;
}

BakeSettings sharing(int rays, float cell, std::uint64_t seed = 0) {
  BakeSettings settings;
  settings.rays = rays;
  settings.sharedReflectionCell = cell;
  settings.transport.seed = seed;
  return settings;
}

// Cells far smaller than the spacing of first hits hold one sample each: every ray reflects its
// own path's light again, so the bake is the unshared one but for float rounding (the light is
// divided by the albedo and multiplied back, and added to what the ray saw after its paths).
TEST(SharedReflections, CellsOfOneSampleGiveEachRayItsOwnPath) {
  const Scene scene = loadGltf(test::sourcePath("data/default_room/default_room.gltf"));
  const RayTracer tracer(scene);
  const ShBasis basis(2);
  const std::vector<ProbeTask> tasks = block(scene.bounds.center(), 0.5f);
  const BakedProbes own = bakeTasks(scene, tracer, basis, sharing(256, 0.0f), tasks);
  const BakedProbes shared = bakeTasks(scene, tracer, basis, sharing(256, 1e-6f), tasks);
  EXPECT_EQ(shared.rays.total(), own.rays.total());
  double largest = 0.0;
  for (std::size_t p = 0; p < tasks.size(); ++p)
    for (std::size_t r = 0; r < own.samples[p].radiance.size(); ++r) {
      const Eigen::Vector3f a = own.samples[p].radiance[r], b = shared.samples[p].radiance[r];
      largest = std::max(largest, double((a - b).cwiseAbs().maxCoeff() / std::max(a.maxCoeff(), 1e-6f)));
    }
  EXPECT_LT(largest, 1e-5) << "a ray's light differs from its own path's";
  EXPECT_GT(largest, 0.0) << "the rays were not shared at all";
}

// furnace: a closed cube emitting 1 with albedo 0.5 everywhere. The light arriving at every
// surface point is the same, so averaging it over cells as large as a wall adds no bias: with
// at most k reflections E(n) = π(1 − ρ^(k+1))/(1 − ρ) for every normal, as without sharing
// (LightTransport.FurnaceMatchesTheGeometricSeries, the same rays and tolerance). Shared is what
// the first hit receives after another reflection, so k ≥ 2.
TEST(SharedReflections, TheFurnaceKeepsItsGeometricSeries) {
  REQUIRE_SHARED_DATA();
  const Scene scene = loadGltf(test::sharedDataPath("scenes/furnace/furnace.gltf"));
  const RayTracer tracer(scene);
  const ShBasis basis(2);
  for (int k : {2, 3}) {
    BakeSettings settings = sharing(16384, 0.75f);
    settings.transport.bounces = k;
    const BakedProbes baked = bakeTasks(scene, tracer, basis, settings, block(Eigen::Vector3f::Zero(), 0.4f));
    const double expected = M_PI * (1.0 - std::pow(0.5, k + 1)) / 0.5;
    for (std::size_t p = 0; p < baked.samples.size(); ++p)
      for (const Eigen::Vector3f& n : kAxes)
        EXPECT_NEAR(sampledIrradiance(baked.samples[p], n).x(), expected, 0.005 * expected)
            << "k = " << k << ", probe " << p;
  }
}

// default_room, lit by its ceiling panel: a probe's irradiance over 16 seeds spreads less when
// the 27 probes of a block share cells of 25 cm than when each keeps its own paths, at the same
// rays (standard deviation 0.038 against 0.088); and the means of the two agree within their
// combined standard errors. The noise is heavy-tailed (paths that find the bright ring the
// panel's back lights on the ceiling): 8 seeds read the unshared deviation as 0.021.
TEST(SharedReflections, SharingLowersTheNoiseOfTheSameMean) {
  const Scene scene = loadGltf(test::sourcePath("data/default_room/default_room.gltf"));
  const RayTracer tracer(scene);
  const ShBasis basis(2);
  const std::vector<ProbeTask> tasks = block(scene.bounds.center(), 0.5f);
  const Eigen::Vector3f down(0, -1, 0);
  constexpr int kSeeds = 16;
  double sum[2] = {0, 0}, squares[2] = {0, 0};
  for (int shared = 0; shared < 2; ++shared)
    for (std::uint64_t seed = 0; seed < kSeeds; ++seed) {
      const BakedProbes baked = bakeTasks(scene, tracer, basis, sharing(512, shared ? 0.25f : 0.0f, seed), tasks);
      const double e = sampledIrradiance(baked.samples[13], down).sum();  // the centre probe, facing the floor
      sum[shared] += e;
      squares[shared] += e * e;
    }
  double mean[2], variance[2];
  for (int s = 0; s < 2; ++s) {
    mean[s] = sum[s] / kSeeds;
    variance[s] = (squares[s] - kSeeds * mean[s] * mean[s]) / (kSeeds - 1);
  }
  EXPECT_LT(variance[1], 0.5 * variance[0]) << "sharing did not halve the variance";
  EXPECT_NEAR(mean[1], mean[0], 3.0 * std::sqrt((variance[0] + variance[1]) / kSeeds));
}

}  // namespace
}  // namespace baker
