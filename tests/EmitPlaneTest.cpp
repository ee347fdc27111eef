#include <gtest/gtest.h>

#include "bake/Baker.h"
#include "bake/DirectionSet.h"
#include "bake/ProbeTracer.h"
#include "bake/ShBasis.h"
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
  const ProbeTracer probe(scene, tracer, dirs);
  std::vector<Eigen::Vector3f> radiance(dirs.size());
  probe.trace(Eigen::Vector3f::Zero(), radiance.data());

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
    }
  }
  EXPECT_GT(above, 900);
  EXPECT_GT(below, 1000);
}

// A half-space of constant radiance L has SH coefficients L·√π for Y00 and L·√(3π)/2 for the
// band-1 function pointing into it; the bake must agree to the accuracy of 4096 samples.
TEST(EmitPlane, BakedShL2MatchesTheHemisphereIntegral) {
  REQUIRE_SHARED_DATA();
  const Scene scene = loadGltf(test::sharedDataPath("scenes/emit_plane/emit_plane.gltf"));
  const RayTracer tracer(scene);
  ProbeGrid grid;  // one probe at the origin
  const ShBasis basis(2);
  const Volume volume = bakeVolume(scene, tracer, basis, grid, 4096, nullptr);
  const float* c = volume.probe(0);
  const float radiance[3] = {0.4f, 2.0f, 3.6f};
  for (int ch = 0; ch < 3; ++ch) {
    const float* coef = c + basis.coefficientOffset(ch);
    // The plane is finite (±50 m), so a sliver near the horizon is missing: 2 % tolerance.
    EXPECT_NEAR(coef[0], radiance[ch] * std::sqrt(M_PI), 0.02 * radiance[ch] * std::sqrt(M_PI)) << "channel " << ch;
    EXPECT_NEAR(coef[1], radiance[ch] * std::sqrt(3 * M_PI) / 2, 0.02 * radiance[ch]) << "channel " << ch;  // Y(1,-1) ∝ y
    EXPECT_NEAR(coef[2], 0.0f, 0.02 * radiance[ch]);
    EXPECT_NEAR(coef[3], 0.0f, 0.02 * radiance[ch]);
  }
}

}  // namespace
}  // namespace baker
