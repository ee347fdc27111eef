#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "bake/EmitterSampler.h"
#include "scene/Environment.h"

namespace baker {
namespace {

// `count` separate triangles of different sizes, each with its own emissive material. Powers
// span eight orders of magnitude: one triangle outshines all the others together, so most of
// them share a few of the guide table's buckets, and some buckets hold none.
Scene manyEmitters(int count) {
  Scene scene;
  Mesh mesh;
  for (int k = 0; k < count; ++k) {
    const float size = 1.0f + 0.3f * float(k % 7);
    const int first = int(mesh.positions.size());
    mesh.positions.push_back({0.0f, 0.0f, float(k)});
    mesh.positions.push_back({size, 0.0f, float(k)});
    mesh.positions.push_back({0.0f, size, float(k)});
    mesh.triangles.push_back({first, first + 1, first + 2});
    mesh.triangleMaterial.push_back(std::uint32_t(k));
    Material material;
    const float strength = k == count / 3 ? 1e6f : k % 5 == 0 ? 1e-2f : 1.0f + float(k % 11);
    material.emission = Eigen::Vector3f::Constant(strength);
    scene.materials.push_back(material);
  }
  mesh.alphaTestedBegin = std::uint32_t(count);
  scene.meshes.push_back(mesh);
  scene.instances.push_back(Instance{});
  return scene;
}

// The emitter chosen for a number x in [0, 1) inverts the running sum of the emitters'
// probabilities: sweeping x over a fine grid chooses the emitters in order, each for as much of
// the grid as its share of power (to the grid's resolution).
TEST(EmitterSampler, ChoosesEachEmitterForItsShareOfPower) {
  for (int count : {1, 2, 3, 8, 9, 10, 500}) {
    const Scene scene = manyEmitters(count);
    const EmitterSampler sampler(scene);
    ASSERT_EQ(sampler.size(), std::size_t(count));
    // Each triangle's share of power, as the sampler is meant to choose them.
    std::vector<double> shares;
    double total = 0.0;
    for (int k = 0; k < count; ++k) {
      const double size = 1.0 + 0.3 * double(k % 7);
      shares.push_back(0.5 * size * size * luminance(scene.materials[k].emission));
      total += shares.back();
    }
    constexpr int kSteps = 1 << 20;
    std::vector<int> chosen(count, 0);
    std::uint32_t previous = 0;
    for (int k = 0; k < kSteps; ++k) {
      const float x = (float(k) + 0.5f) / float(kSteps);
      const std::uint32_t triangle = sampler.sample(x, 0.25f, 0.5f).emitter->triangle;
      ASSERT_GE(triangle, previous) << "not monotonic at x = " << x;
      previous = triangle;
      ++chosen[triangle];
    }
    for (int k = 0; k < count; ++k)
      EXPECT_NEAR(double(chosen[k]) / kSteps, shares[k] / total, 1.0 / kSteps + 1e-6 * shares[k] / total)
          << "triangle " << k << " of " << count;
  }
}

// Equal powers put the running sums exactly on the guide table's bucket edges, k/16: a number
// on an edge is past the sum there (std::upper_bound), one just below it is not.
TEST(EmitterSampler, NumbersOnABucketEdgeChooseTheEmitterAfterIt) {
  constexpr int kCount = 16;
  Scene scene;
  Mesh mesh;
  for (int k = 0; k < kCount; ++k) {
    mesh.positions.push_back({0.0f, 0.0f, float(k)});
    mesh.positions.push_back({1.0f, 0.0f, float(k)});
    mesh.positions.push_back({0.0f, 1.0f, float(k)});
    mesh.triangles.push_back({3 * k, 3 * k + 1, 3 * k + 2});
    mesh.triangleMaterial.push_back(0);
  }
  mesh.alphaTestedBegin = kCount;
  scene.meshes.push_back(mesh);
  scene.instances.push_back(Instance{});
  Material material;
  material.emission = Eigen::Vector3f::Ones();
  scene.materials.push_back(material);
  const EmitterSampler sampler(scene);
  for (std::uint32_t k = 1; k < kCount; ++k) {
    const float edge = float(k) / kCount;
    EXPECT_EQ(sampler.sample(edge, 0.5f, 0.5f).emitter->triangle, k) << "x = " << edge;
    EXPECT_EQ(sampler.sample(std::nextafter(edge, 0.0f), 0.5f, 0.5f).emitter->triangle, k - 1) << "below " << edge;
  }
}

// An emitter whose power overflows single precision makes every running sum after it infinite:
// those sums still sort above every number, so the search does what it does for finite sums
// (here, all but the smallest numbers choose that emitter) instead of misplacing the sums.
TEST(EmitterSampler, AnEmitterWhosePowerOverflowsKeepsTheSearchInOrder) {
  Scene scene = manyEmitters(20);
  for (Eigen::Vector3f& p : scene.meshes[0].positions)
    if (p.z() == 5.0f) p.head<2>() *= 100.0f;
  scene.materials[5].emission = Eigen::Vector3f::Constant(3e38f);
  const EmitterSampler sampler(scene);
  for (int k = 1; k < 1024; ++k)
    ASSERT_EQ(sampler.sample(float(k) / 1024, 0.5f, 0.5f).emitter->triangle, 5u) << "x = " << float(k) / 1024;
}

// Extreme numbers still land on an emitter: 0 on the first with any power, the largest float
// below 1 on the last.
TEST(EmitterSampler, TheEndsOfTheUnitIntervalChooseTheFirstAndLastEmitters) {
  const Scene scene = manyEmitters(500);
  const EmitterSampler sampler(scene);
  const EmitterSampler::Emitter* first = sampler.sample(0.0f, 0.5f, 0.5f).emitter;
  const EmitterSampler::Emitter* last = sampler.sample(std::nextafter(1.0f, 0.0f), 0.5f, 0.5f).emitter;
  EXPECT_EQ(first->triangle, 0u);
  EXPECT_EQ(last->triangle, 499u);
}

}  // namespace
}  // namespace baker
