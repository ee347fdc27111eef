#include <gtest/gtest.h>

#include <vector>

#include "bake/PathIntegrator.h"
#include "basis/DirectionSet.h"
#include "scene/GltfLoader.h"
#include "scene/RayTracer.h"
#include "tests/TestData.h"

namespace baker {
namespace {

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
