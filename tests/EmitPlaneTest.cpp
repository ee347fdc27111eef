#include <gtest/gtest.h>

#include "bake/Baker.h"
#include "bake/PathIntegrator.h"
#include "basis/DirectionSet.h"
#include "basis/ShBasis.h"
#include "scene/GltfLoader.h"
#include "scene/RayTracer.h"
#include "tests/TestData.h"

namespace baker {
namespace {

// emit_plane: a 100 m emissive plane at y = 1, emissive (0.1, 0.5, 0.9) × strength 4.
TEST(EmitPlane, ProbeAtOriginSeesThePlaneAboveAndNothingBelow) {
  REQUIRE_SHARED_DATA();
  const Scene scene = loadGltf(test::sharedDataPath("scenes/emit_plane/emit_plane.gltf"));
  const RayTracer tracer(scene);
  std::vector<Eigen::Vector3f> dirs;
  for (const Eigen::Vector3d& d : sphericalFibonacci(2048).directions) dirs.push_back(d.cast<float>());
  const PathIntegrator probe(scene, tracer, TransportSettings{});
  std::vector<Eigen::Vector3f> radiance(dirs.size());
  std::vector<float> visibility(dirs.size());
  RayCounts counts;
  probe.trace(Eigen::Vector3f::Zero(), 0, dirs.data(), int(dirs.size()), radiance.data(), visibility.data(), &counts);

  int above = 0, below = 0;
  for (std::size_t k = 0; k < dirs.size(); ++k) {
    if (dirs[k].y() > 0.03f) {  // steeper than the plane's edge, 50 m out at 1 m height
      ++above;
      EXPECT_NEAR(radiance[k].x(), 0.4f, 1e-6f);
      EXPECT_NEAR(radiance[k].y(), 2.0f, 1e-6f);
      EXPECT_NEAR(radiance[k].z(), 3.6f, 1e-6f);
    } else if (dirs[k].y() < 0.0f) {
      ++below;
      EXPECT_EQ(radiance[k], Eigen::Vector3f::Zero());
      EXPECT_EQ(visibility[k], 1.0f);
    }
  }
  EXPECT_GT(above, 900);
  EXPECT_GT(below, 1000);
}

// Radiance L from the whole upper half-space gives the irradiance E(n) = πL(1 + n_y)/2, which
// lies in the span of SH L1, so the baked sh-l2 volume must reconstruct it at any normal.
TEST(EmitPlane, BakedIrradianceMatchesTheHalfSpaceClosedForm) {
  REQUIRE_SHARED_DATA();
  const Scene scene = loadGltf(test::sharedDataPath("scenes/emit_plane/emit_plane.gltf"));
  const RayTracer tracer(scene);
  ProbeGrid grid;  // one probe at the origin
  const ShBasis basis(2);
  BakeSettings settings;
  settings.rays = 4096;
  const Volume volume = bakeVolume(scene, tracer, basis, grid, settings, nullptr);
  const Eigen::Vector3f radiance(0.4f, 2.0f, 3.6f);
  for (const Eigen::Vector3d& n : {Eigen::Vector3d(0, 1, 0), Eigen::Vector3d(0, -1, 0), Eigen::Vector3d(1, 0, 0),
                                   Eigen::Vector3d(0, 0.6, -0.8), Eigen::Vector3d(-0.6, -0.8, 0)}) {
    const Eigen::Vector3f e = basis.reconstruct(volume.probe(0), n);
    const Eigen::Vector3f expected = radiance * float(M_PI * (1.0 + n.y()) / 2.0);
    // The plane ends 50 m out at 1 m height: the sliver it misses near the horizon is < 2 %
    // of the upward irradiance, and the 4096-ray quadrature adds well under that.
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(e[c], expected[c], 0.02 * M_PI * radiance[c]) << "normal " << n.transpose() << " channel " << c;
  }
}

}  // namespace
}  // namespace baker
