#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <random>

#include "scene/GltfLoader.h"
#include "scene/RayRecorder.h"
#include "scene/RayTracer.h"
#include "tests/GltfTestAssets.h"
#include "tests/TestData.h"

namespace baker {
namespace {

using test::GltfBuilder;

class SceneRayTracer : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = test::makeTempDir(::testing::UnitTest::GetInstance()->current_test_info()->name()); }
  std::string dir_;
};

// A 2 × 2 m square facing +Z at z = 0 with an alpha texture: left half alpha 0, right half 1,
// MASK; behind it (z = −1) an opaque square of the same size; the square mesh is used twice.
Scene maskedScene(GltfBuilder& gltf, const std::string& dir) {
  const int texture = gltf.texture(test::encodePng(2, 1, 4, {255, 255, 255, 0, 255, 255, 255, 255}),
                                   {{"magFilter", 9728}});
  const int mask = gltf.material({{"alphaMode", "MASK"}, {"pbrMetallicRoughness", {{"baseColorTexture", {{"index", texture}}}}}});
  const int opaque = gltf.material({{"pbrMetallicRoughness", {{"baseColorFactor", {0.5, 0.5, 0.5, 1}}}}});
  gltf.node({{"mesh", test::squareMesh(gltf, 2.0f, mask)}});
  const int back = test::squareMesh(gltf, 2.0f, opaque);
  gltf.node({{"mesh", back}, {"translation", {0, 0, -1}}});
  gltf.node({{"mesh", back}, {"translation", {0, 0, -2}}});
  return loadGltf(gltf.write(dir, "masked"));
}

TEST_F(SceneRayTracer, MaskFilterLetsRaysThroughTransparentTexels) {
  GltfBuilder gltf;
  const Scene scene = maskedScene(gltf, dir_);
  const RayTracer tracer(scene);
  EXPECT_EQ(tracer.filteredGeometries(), 1) << "only the MASK geometry carries a filter";
  EXPECT_EQ(tracer.instancedMeshes(), 1);
  const Eigen::Vector3f down(0, 0, -1);
  Hit hit;
  tracer.intersect8(Eigen::Vector3f(0.5f, 1.0f, 1.0f), &down, 1, &hit);  // left half: transparent
  ASSERT_FALSE(hit.missed());
  EXPECT_EQ(hit.instance, 1u);
  EXPECT_FLOAT_EQ(hit.distance, 2.0f);
  tracer.intersect8(Eigen::Vector3f(1.5f, 1.0f, 1.0f), &down, 1, &hit);  // right half: opaque
  ASSERT_FALSE(hit.missed());
  EXPECT_EQ(hit.instance, 0u);
  EXPECT_FLOAT_EQ(hit.distance, 1.0f);

  // Occlusion agrees: a shadow ray ending between the two squares is blocked only on the right.
  const Ray rays[2] = {{{0.5f, 1.0f, 1.0f}, down, 0.0f, 1.5f}, {{1.5f, 1.0f, 1.0f}, down, 0.0f, 1.5f}};
  bool blocked[2];
  tracer.occluded(rays, 2, blocked);
  EXPECT_FALSE(blocked[0]);
  EXPECT_TRUE(blocked[1]);
}

TEST_F(SceneRayTracer, OccludedAgreesWithClosestHitsForManyRays) {
  GltfBuilder gltf;
  const Scene scene = maskedScene(gltf, dir_);
  const RayTracer tracer(scene);
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::vector<Ray> rays;
  std::vector<Hit> hits;
  for (int k = 0; k < 1000; ++k) {
    Ray r;
    r.origin = Eigen::Vector3f(1 + u(rng), 1 + u(rng), 0.5f + u(rng));
    r.direction = Eigen::Vector3f(u(rng), u(rng), u(rng)).normalized();
    r.tfar = 1.0f + u(rng);
    Hit hit;
    tracer.intersect8(r.origin, &r.direction, 1, &hit);
    rays.push_back(r);
    hits.push_back(hit);
  }
  std::unique_ptr<bool[]> blocked(new bool[rays.size()]);
  tracer.occluded(rays.data(), int(rays.size()), blocked.get());
  int disagreements = 0;
  for (std::size_t k = 0; k < rays.size(); ++k)
    disagreements += blocked[k] != (!hits[k].missed() && hits[k].distance < rays[k].tfar);
  EXPECT_EQ(disagreements, 0);
}

TEST_F(SceneRayTracer, BlendCoverageIsStochasticDeterministicAndMatchesAlpha) {
  GltfBuilder gltf;
  const int blend = gltf.material({{"alphaMode", "BLEND"}, {"pbrMetallicRoughness", {{"baseColorFactor", {1, 1, 1, 0.3}}}}});
  gltf.node({{"mesh", test::squareMesh(gltf, 100.0f, blend)}, {"translation", {-50, -50, 0}}});
  const Scene scene = loadGltf(gltf.write(dir_, "blend"));
  const RayTracer tracer(scene);
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::vector<Ray> rays(20000);
  for (Ray& r : rays) {
    r.origin = Eigen::Vector3f(u(rng), u(rng), 1.0f);
    r.direction = Eigen::Vector3f(0.3f * u(rng), 0.3f * u(rng), -1.0f).normalized();
  }
  const std::size_t n = rays.size();
  std::unique_ptr<bool[]> first(new bool[n]), second(new bool[n]);
  tracer.occluded(rays.data(), int(n), first.get());
  tracer.occluded(rays.data(), int(n), second.get());
  EXPECT_TRUE(std::equal(first.get(), first.get() + n, second.get())) << "coverage depends on the ray alone";
  const double fraction = std::count(first.get(), first.get() + n, true) / double(n);
  // Binomial: σ = √(0.3 · 0.7 / 20000) ≈ 0.0032.
  EXPECT_NEAR(fraction, 0.3, 0.016);
}

// alpha_fence: a 4 × 2 m fence (x ∈ [−2, 2], y ∈ [0, 2], z = 0, u = (x + 2)/4, v = 1 − y/2)
// with a 64 × 64 checker of alpha 255 and 40, MASK at 0.5, NEAREST: a ray through each texel
// centre passes exactly where the texel is transparent, half of them.
TEST_F(SceneRayTracer, AlphaFencePassesExactlyTheTransparentTexels) {
  REQUIRE_SHARED_DATA();
  const Scene scene = loadGltf(test::sharedDataPath("scenes/alpha_fence/alpha_fence.gltf"));
  const RayTracer tracer(scene);
  EXPECT_EQ(tracer.filteredGeometries(), 1);
  const Eigen::Vector3f back(0, 0, -1);
  std::vector<Ray> rays;
  int passed = 0;
  for (int j = 0; j < 64; ++j)
    for (int i = 0; i < 64; ++i) {
      const Eigen::Vector3f origin(-2.0f + 4.0f * (i + 0.5f) / 64, 2.0f * (1.0f - (j + 0.5f) / 64), 1.0f);
      Hit hit;
      tracer.intersect8(origin, &back, 1, &hit);
      passed += hit.missed();
      rays.push_back({origin, back, 0.0f, 2.0f});
    }
  EXPECT_EQ(passed, 64 * 64 / 2);
  std::unique_ptr<bool[]> blocked(new bool[rays.size()]);
  tracer.occluded(rays.data(), int(rays.size()), blocked.get());
  EXPECT_EQ(std::count(blocked.get(), blocked.get() + rays.size(), false), 64 * 64 / 2);
}

TEST_F(SceneRayTracer, OpaqueScenesCarryNoFilters) {
  GltfBuilder gltf;
  gltf.node({{"mesh", gltf.mesh({{"POSITION", gltf.floats(test::triangleXY(), "VEC3")}})}});
  const Scene scene = loadGltf(gltf.write(dir_, "opaque"));
  const RayTracer tracer(scene);
  EXPECT_EQ(tracer.filteredGeometries(), 0);
  EXPECT_EQ(tracer.instancedMeshes(), 0);
}

// bench_bake's hooks: recording a bake's rays and timing Embree's calls must change no result,
// the log must hold every ray in the calls that traced it, and the clock must run only while on.
TEST_F(SceneRayTracer, RecordingAndTimingTracesChangeNoResult) {
  GltfBuilder gltf;
  const Scene scene = maskedScene(gltf, dir_);
  RayRecorder recorder;
  const RayTracer tracer(scene, true, &recorder);
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::vector<Ray> rays(21);
  for (Ray& r : rays) {
    r.origin = Eigen::Vector3f(1 + u(rng), 1 + u(rng), 0.5f + u(rng));
    r.direction = Eigen::Vector3f(u(rng), u(rng), u(rng) - 1.5f).normalized();
    r.tfar = 2.0f + u(rng);
  }
  auto traceAll = [&](std::vector<Hit>* hits, std::vector<char>* blocked) {
    hits->assign(rays.size(), Hit{});
    for (std::size_t first = 0; first < rays.size(); first += 8)
      tracer.intersect8(rays.data() + first, int(std::min<std::size_t>(8, rays.size() - first)), hits->data() + first);
    std::unique_ptr<bool[]> flags(new bool[rays.size()]);
    tracer.occluded(rays.data(), int(rays.size()), flags.get());
    blocked->assign(flags.get(), flags.get() + rays.size());
  };
  std::vector<Hit> plainHits, watchedHits;
  std::vector<char> plainBlocked, watchedBlocked;
  traceAll(&plainHits, &plainBlocked);

  RayLog log;
  double seconds = 0.0;
  recorder.record(&log);
  recorder.timeEmbreeCalls(&seconds);
  traceAll(&watchedHits, &watchedBlocked);
  recorder.record(nullptr);
  recorder.timeEmbreeCalls(nullptr);

  int hitCount = 0;
  for (std::size_t k = 0; k < rays.size(); ++k) {
    EXPECT_EQ(watchedHits[k].triangle, plainHits[k].triangle) << "ray " << k;
    EXPECT_EQ(watchedHits[k].instance, plainHits[k].instance) << "ray " << k;
    EXPECT_EQ(watchedHits[k].distance, plainHits[k].distance) << "ray " << k;
    EXPECT_EQ(watchedBlocked[k], plainBlocked[k]) << "ray " << k;
    hitCount += !plainHits[k].missed();
  }
  EXPECT_GT(hitCount, 0);
  EXPECT_LT(hitCount, int(rays.size())) << "the rays should both hit and miss";
  EXPECT_EQ(log.packetSizes, (std::vector<int>{8, 8, 5}));
  EXPECT_EQ(log.streamSizes, (std::vector<int>{21}));
  ASSERT_EQ(log.closest.size(), rays.size());
  ASSERT_EQ(log.occlusion.size(), rays.size());
  for (std::size_t k = 0; k < rays.size(); ++k) {
    EXPECT_EQ(log.closest[k].direction, rays[k].direction);
    EXPECT_EQ(log.occlusion[k].tfar, rays[k].tfar);
  }
  EXPECT_GT(seconds, 0.0);
  const double stopped = seconds;
  traceAll(&watchedHits, &watchedBlocked);
  EXPECT_EQ(seconds, stopped) << "the clock ran after it was stopped";
  EXPECT_EQ(log.closest.size(), rays.size()) << "rays were recorded after recording stopped";
}

}  // namespace
}  // namespace baker
