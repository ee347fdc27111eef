#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "bake/PathIntegrator.h"
#include "bake/PathRandom.h"
#include "basis/DirectionSet.h"
#include "scene/GltfLoader.h"
#include "scene/RayTracer.h"
#include "tests/TestData.h"

namespace baker {
namespace {

// A path's numbers come two from one scrambled counter (PathRandom::uniformPair): each of the
// pair must be uniform on its own and the two independent, or the directions and points drawn
// from them would cluster. Pairs in a 32 × 32 grid against the uniform density: Pearson's χ² over
// its 1023 degrees of freedom stays below 1200 (p ≈ 1e-4 by the normal approximation); each
// number's mean is ½ within 4 standard errors, their correlation 0 within 4/√n; draws of a
// scalar and of a pair advance one counter alike.
TEST(PathRandom, PairsAreUniformAndIndependent) {
  constexpr int kCells = 32, kPairs = 1 << 20;
  std::vector<int> cells(kCells * kCells, 0);
  double sumA = 0.0, sumB = 0.0, sumAB = 0.0;
  int draws = 0;
  for (std::uint64_t path = 0; draws < kPairs; ++path) {
    PathRandom random(7, 3, path);
    for (int d = 0; d < 16; ++d, ++draws) {
      float a, b;
      random.uniformPair(&a, &b);
      ASSERT_TRUE(a >= 0.0f && a < 1.0f && b >= 0.0f && b < 1.0f);
      ++cells[int(a * kCells) * kCells + int(b * kCells)];
      sumA += a, sumB += b, sumAB += double(a) * b;
    }
  }
  const double expected = double(kPairs) / (kCells * kCells);
  double chiSquare = 0.0;
  for (int c : cells) chiSquare += (c - expected) * (c - expected) / expected;
  EXPECT_LT(chiSquare, 1200.0);
  const double n = kPairs, meanA = sumA / n, meanB = sumB / n;
  EXPECT_NEAR(meanA, 0.5, 4.0 * std::sqrt(1.0 / 12.0 / n));
  EXPECT_NEAR(meanB, 0.5, 4.0 * std::sqrt(1.0 / 12.0 / n));
  EXPECT_NEAR((sumAB / n - meanA * meanB) * 12.0, 0.0, 4.0 / std::sqrt(n));
  PathRandom pairs(1, 2, 3), scalars(1, 2, 3);
  float a, b;
  pairs.uniformPair(&a, &b);
  EXPECT_EQ(a, scalars.uniform()) << "a pair's first number is the scalar draw's";
  EXPECT_EQ(pairs.uniform(), scalars.uniform()) << "a pair advances the counter as one scalar draw does";
}

// A path's stream is splitmix64's finaliser (Steele, Lea and Flood 2014; written out here from
// its published constants) applied to a counter that advances by PathRandom's odd step, started
// at the scrambled (seed, probe, ray): volumes record it as their sampler, so neither way of
// starting one, with the probe's part worked out per path or once per probe (fromProbeKey), may
// move it by a bit.
TEST(PathRandom, IsSplitMix64StartedAtTheScrambledSeedProbeAndRay) {
  const auto mix = [](std::uint64_t z) {
    z += 0x9e3779b97f4a7c15ull;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
  };
  const std::uint64_t triples[][3] = {{0, 0, 0}, {1, 2, 3}, {7, 3071, 255}, {~0ull, 1ull << 40, 65535}};
  for (const auto& t : triples) {
    std::uint64_t state = mix(mix(mix(t[0]) ^ t[1]) ^ t[2]);
    PathRandom direct(t[0], t[1], t[2]);
    PathRandom keyed = PathRandom::fromProbeKey(PathRandom::probeKey(t[0], t[1]), t[2]);
    for (int d = 0; d < 4; ++d) {
      state += 0x632be59bd9b4e019ull;
      const float expected = float(mix(state) >> 40) * (1.0f / 16777216.0f);
      EXPECT_EQ(direct.uniform(), expected) << "seed " << t[0] << ", probe " << t[1] << ", ray " << t[2] << ", draw " << d;
      EXPECT_EQ(keyed.uniform(), expected) << "seed " << t[0] << ", probe " << t[1] << ", ray " << t[2] << ", draw " << d;
    }
  }
}

// The integrator shades paths eight at a time in SIMD lanes, and compacts them as they end, so
// a path shares lanes with different paths depending on how many are traced together. Its
// radiance must still depend on (seed, probe, ray) alone, to the bit: that is what makes a bake
// identical at any thread count and batch size.
TEST(PathIntegrator, APathsRadianceDoesNotDependOnThePathsTracedBesideIt) {
  const Scene scene = loadGltf(test::sourcePath("data/default_room/default_room.gltf"));
  const RayTracer tracer(scene);
  const PathIntegrator integrator(scene, tracer, TransportSettings{});
  std::vector<Eigen::Vector3f> directions;
  for (const Eigen::Vector3d& d : sphericalFibonacci(37).directions) directions.push_back(d.cast<float>());
  const Eigen::Vector3f position(0.3f, 1.2f, 1.7f);
  const int all = int(directions.size());
  std::vector<Eigen::Vector3f> radiance(directions.size());
  std::vector<float> visibility(directions.size());
  RayCounts counts;
  integrator.trace(position, 7, directions.data(), all, radiance.data(), visibility.data(), &counts);
  // The room's panel lights it through emitter samples and reflections: both lane stretches ran.
  ASSERT_GT(counts.emitterShadow, 0);
  ASSERT_GT(counts.bounce, 0);
  for (int count : {1, 5, 8, 9, 20}) {
    std::vector<Eigen::Vector3f> part(static_cast<std::size_t>(count));
    std::vector<float> partVisibility(static_cast<std::size_t>(count));
    RayCounts partCounts;
    integrator.trace(position, 7, directions.data(), count, part.data(), partVisibility.data(), &partCounts);
    for (int i = 0; i < count; ++i) {
      for (int c = 0; c < 3; ++c) EXPECT_EQ(part[i][c], radiance[i][c]) << "ray " << i << " of " << count;
      EXPECT_EQ(partVisibility[i], visibility[i]) << "ray " << i << " of " << count;
    }
  }
  int lit = 0;
  for (const Eigen::Vector3f& l : radiance) lit += l.maxCoeff() > 0.0f ? 1 : 0;
  EXPECT_GT(lit, all / 2) << "the panel lights most paths: the comparisons above are not of zeros";
}

}  // namespace
}  // namespace baker
