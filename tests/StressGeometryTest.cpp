// Geometry that strains a ray tracer: triangles of zero area, slivers five thousand times
// longer than wide, needles whose area all but underflows, two surfaces in one plane, and one
// primitive of two million triangles. Each loads, bakes finite, and bakes what it should.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <filesystem>

#include "bake/Baker.h"
#include "basis/BasisRegistry.h"
#include "scene/GltfLoader.h"
#include "scene/RayTracer.h"
#include "tests/GltfTestAssets.h"
#include "tests/OnThreads.h"
#include "tests/TestData.h"
#include "tests/TransportTestSupport.h"

namespace baker {
namespace {

using test::GltfBuilder;

constexpr float kSky = 1.0f;

class StressGeometry : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = test::makeTempDir(::testing::UnitTest::GetInstance()->current_test_info()->name());
    basis_ = makeBasis("sh-l2");
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  Scene loadUnderSky(const std::string& path) const {
    Scene scene = loadGltf(path);
    scene.environment = Environment::constant(Eigen::Vector3f::Constant(kSky));
    return scene;
  }
  // The probe's rays that head down (−Z) and escape.
  static int escapingDownwards(const test::BakedProbe& probe) {
    int escaping = 0;
    for (std::size_t r = 0; r < probe.samples.directions.size(); ++r)
      escaping += probe.samples.directions[r].z() < -0.05f && probe.samples.visibility[r] > 0.0f;
    return escaping;
  }

  std::string dir_;
  std::unique_ptr<Basis> basis_;
};

// The square [−1, 1]² at z = 0, facing +Z, as a fan about its centre with `perSide` vertices
// along each side: triangles 1 to 1.4 long and 2/perSide wide at the rim.
std::vector<float> fanSquare(int perSide) {
  std::vector<Eigen::Vector3f> rim;
  for (int side = 0; side < 4; ++side)
    for (int k = 0; k < perSide; ++k) {
      const float t = -1.0f + 2.0f * float(k) / float(perSide);
      const Eigen::Vector3f corners[4] = {{t, -1, 0}, {1, t, 0}, {-t, 1, 0}, {-1, -t, 0}};
      rim.push_back(corners[side]);
    }
  std::vector<float> positions;
  for (std::size_t k = 0; k < rim.size(); ++k)
    for (const Eigen::Vector3f& p : {Eigen::Vector3f::Zero().eval(), rim[k], rim[(k + 1) % rim.size()]})
      positions.insert(positions.end(), p.data(), p.data() + 3);
  return positions;
}

TEST_F(StressGeometry, ZeroAreaTrianglesAreSkippedWithAWarning) {
  GltfBuilder gltf;
  // Two real triangles, then a repeated corner, three collinear points and a needle whose area
  // underflows single precision: all three of zero area as the loader computes it.
  std::vector<float> positions = test::triangleXY(1.0f);
  const std::vector<float> more = {1, 1, 0, 0, 1, 0, 1, 0, 0,  // a second real one
                                   0, 0, 0, 0, 0, 0, 1, 1, 0,  // a corner twice
                                   0, 0, 0, 1, 1, 0, 2, 2, 0,  // collinear
                                   0, 0, 0, 1, 0, 0, 0.5f, 1e-30f, 0};
  positions.insert(positions.end(), more.begin(), more.end());
  gltf.node({{"mesh", gltf.mesh({{"POSITION", gltf.floats(positions, "VEC3")}})}});
  const Scene scene = loadUnderSky(gltf.write(dir_, "zero_area"));
  EXPECT_EQ(scene.triangleCount(), 2u);
  bool warned = false;
  for (const std::string& w : scene.warnings) warned |= w.find("skipped 3 degenerate triangle(s)") != std::string::npos;
  EXPECT_TRUE(warned);
  const RayTracer tracer(scene);
  const test::BakedProbe probe = test::bakeProbe(scene, tracer, *basis_, {}, Eigen::Vector3f(0.5f, 0.5f, 0.5f));
  for (float c : probe.coefficients) EXPECT_TRUE(std::isfinite(c));
}

// 40 000 slivers (1 to 1.4 m long, 0.2 mm wide at the rim) and needles down to 1e-20 m high
// tile a floor: every normal is a finite unit vector, and no ray slips between neighbours to the sky.
TEST_F(StressGeometry, SliversAndNeedlesLeaveNoCracksAndFiniteNormals) {
  GltfBuilder gltf;
  std::vector<float> positions = fanSquare(10000);
  for (float height : {1e-6f, 1e-12f, 1e-20f}) {
    const std::vector<float> needle = {-1, 0, 0, 1, 0, 0, 0, height, 0};
    positions.insert(positions.end(), needle.begin(), needle.end());
  }
  gltf.node({{"mesh", gltf.mesh({{"POSITION", gltf.floats(positions, "VEC3")}})}});
  const Scene scene = loadUnderSky(gltf.write(dir_, "slivers", true));
  ASSERT_EQ(scene.triangleCount(), 40003u);  // 1e-20 m high still has an area in float: 4e-40
  for (std::uint32_t t = 0; t < scene.meshes[0].triangleCount(); ++t) {
    const Eigen::Vector3f n = scene.frontNormal(0, t);
    ASSERT_TRUE(n.allFinite() && std::abs(n.norm() - 1.0f) < 1e-5f) << "triangle " << t;
  }
  const RayTracer tracer(scene);
  BakeSettings settings;
  settings.rays = 4096;
  for (const Eigen::Vector3f& position : {Eigen::Vector3f(0.0f, 0.0f, 0.05f), Eigen::Vector3f(0.3f, -0.2f, 1e-3f)}) {
    const test::BakedProbe probe = test::bakeProbe(scene, tracer, *basis_, settings, position);
    EXPECT_EQ(escapingDownwards(probe), 0) << position.transpose();
    // Upwards: the whole open sky, E = π·L.
    const Eigen::Vector3f up = basis_->reconstruct(probe.coefficients.data(), Eigen::Vector3d::UnitZ());
    EXPECT_NEAR(up.x(), float(M_PI) * kSky, 0.02f * float(M_PI) * kSky);
  }
}

// Two emitters in one plane, one red and one green: each ray sees one or the other, the lattice's
// and the emitter samples' alike (a sample counts only where its ray first hits the triangle it
// sampled), so red plus green is what one emitter of both gives, to the samples' noise (the two
// scenes sample their emitters differently); and the choice is the same on every run and thread
// count.
TEST_F(StressGeometry, CoincidentSurfacesBakeDeterministicallyAsOneOrTheOther) {
  GltfBuilder gltf;
  const int red = gltf.material({{"emissiveFactor", {1, 0, 0}}, {"doubleSided", true}});
  const int green = gltf.material({{"emissiveFactor", {0, 1, 0}}, {"doubleSided", true}});
  gltf.node({{"mesh", test::squareMesh(gltf, 1.0f, red)}});
  gltf.node({{"mesh", test::squareMesh(gltf, 1.0f, green)}});
  const Scene scene = loadGltf(gltf.write(dir_, "coincident"));
  const RayTracer tracer(scene);
  BakeSettings settings;
  settings.rays = 4096;  // the samples of the two scenes differ: keep their noise under 1 %
  settings.transport.bounces = 0;
  const ProbeGrid grid = makeProbeGrid(scene.bounds, 0.25, 1000);
  const auto bakeWith = [&](int threads) {
    return test::onThreads(threads, [&] { return bakeVolume(scene, tracer, *basis_, grid, settings, nullptr); });
  };
  const Volume one = bakeWith(1), two = bakeWith(2);
  EXPECT_EQ(one.coefficients, two.coefficients);

  GltfBuilder single;
  single.node({{"mesh", test::squareMesh(single, 1.0f, single.material({{"emissiveFactor", {1, 1, 0}},
                                                                         {"doubleSided", true}}))}});
  const Scene yellowScene = loadGltf(single.write(dir_, "yellow"));
  const RayTracer yellowTracer(yellowScene);
  const Volume yellow = bakeVolume(yellowScene, yellowTracer, *basis_, grid, settings, nullptr);
  ASSERT_EQ(yellow.coefficients.size(), one.coefficients.size());
  for (std::int64_t p = 0; p < grid.probeCount(); ++p)
    for (const Eigen::Vector3d& n : {Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(0, 0, -1)}) {
      const Eigen::Vector3f mixed = basis_->reconstruct(one.probe(p), n);
      const Eigen::Vector3f both = basis_->reconstruct(yellow.probe(p), n);
      ASSERT_TRUE(mixed.allFinite());
      EXPECT_NEAR(mixed.x() + mixed.y(), both.x(), 0.01f * std::abs(both.x()) + 1e-3f * float(M_PI)) << "probe " << p;
    }
}

// A 1001 × 1001 height field, 2 000 000 triangles in one primitive, written as a .glb: it loads
// and bakes in seconds (few probes, few rays), and the sky above it is open.
TEST_F(StressGeometry, TwoMillionTrianglesInOnePrimitiveLoadAndBake) {
  constexpr int kSide = 1001;
  std::vector<float> positions;
  positions.reserve(std::size_t(kSide) * kSide * 3);
  for (int j = 0; j < kSide; ++j)
    for (int i = 0; i < kSide; ++i) {
      const float x = 0.1f * float(i), y = 0.1f * float(j);
      positions.insert(positions.end(), {x, y, 0.05f * std::sin(x) * std::cos(y)});
    }
  std::vector<std::uint32_t> indices;
  indices.reserve(std::size_t(kSide - 1) * (kSide - 1) * 6);
  for (int j = 0; j + 1 < kSide; ++j)
    for (int i = 0; i + 1 < kSide; ++i) {
      const std::uint32_t a = std::uint32_t(j * kSide + i), b = a + 1, c = a + kSide, d = c + 1;
      indices.insert(indices.end(), {a, b, d, a, d, c});
    }
  GltfBuilder gltf;
  gltf.node({{"mesh", gltf.mesh({{"POSITION", gltf.floats(positions, "VEC3")}}, gltf.indices(indices))}});
  const std::string path = gltf.writeGlb(dir_, "terrain");
  positions = {};
  indices = {};

  const auto start = std::chrono::steady_clock::now();
  const Scene scene = loadUnderSky(path);
  ASSERT_EQ(scene.triangleCount(), 2000000u);
  const RayTracer tracer(scene);
  BakeSettings settings;
  settings.rays = 64;
  settings.transport.bounces = 1;
  ProbeGrid grid;  // four probes a metre above the field
  grid.dims = {2, 2, 1};
  grid.origin = {25.0, 25.0, 1.0};
  grid.spacing = 50.0;
  const Volume volume = bakeVolume(scene, tracer, *basis_, grid, settings, nullptr);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  RecordProperty("load_and_bake_seconds", fmt::format("{:.2f}", seconds));
  EXPECT_LT(seconds, 120.0);
  for (std::int64_t p = 0; p < grid.probeCount(); ++p) {
    EXPECT_EQ(volume.states[p], ProbeState::Valid);
    const Eigen::Vector3f up = basis_->reconstruct(volume.probe(p), Eigen::Vector3d::UnitZ());
    ASSERT_TRUE(up.allFinite());
    EXPECT_NEAR(up.x(), float(M_PI) * kSky, 0.05f * float(M_PI) * kSky) << "probe " << p;
  }
}

}  // namespace
}  // namespace baker
