#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "bake/ProbeValidity.h"
#include "scene/GltfLoader.h"
#include "scene/RayTracer.h"
#include "tests/GltfTestAssets.h"
#include "volume/InvalidProbeFill.h"
#include "tests/TestData.h"

namespace baker {
namespace {

using test::GltfBuilder;

class ProbeValidity : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = test::makeTempDir(::testing::UnitTest::GetInstance()->current_test_info()->name()); }

  // Places one probe with the default options, counting the rays it traced.
  ProbePlacement place(const RayTracer& tracer, const Eigen::Vector3f& position, float spacing) {
    return placeProbe(tracer, position, spacing, directions_, options_, &raysTraced_);
  }

  std::string dir_;
  ValidityOptions options_;
  std::vector<Eigen::Vector3f> directions_ = validityDirections(options_);
  std::int64_t raysTraced_ = 0;
};

// The box [centre − half, centre + half]³ as 12 unindexed triangles whose front faces point
// outward (a solid object) or inward (a room).
int boxMesh(GltfBuilder& gltf, const Eigen::Vector3f& centre, float half, bool outward) {
  std::vector<float> positions;
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      const auto corner = [&](int cu, int cv) {
        Eigen::Vector3f p = centre;
        p[axis] += side ? half : -half;
        p[u] += cu ? half : -half;
        p[v] += cv ? half : -half;
        return p;
      };
      // Counter-clockwise in (u, v) faces +axis, since u × v = axis.
      Eigen::Vector3f quad[4] = {corner(0, 0), corner(1, 0), corner(1, 1), corner(0, 1)};
      if ((side == 1) != outward) std::swap(quad[1], quad[3]);
      for (const int c : {0, 1, 2, 0, 2, 3}) positions.insert(positions.end(), quad[c].data(), quad[c].data() + 3);
    }
  return gltf.mesh({{"POSITION", gltf.floats(positions, "VEC3")}});
}

// A 100 m square in the plane x = `x`, facing +X.
int wallFacingPlusX(GltfBuilder& gltf, float x) {
  const float s = 50.0f;
  return gltf.mesh({{"POSITION", gltf.floats({x, -s, -s, x, s, -s, x, s, s, x, -s, -s, x, s, s, x, -s, s}, "VEC3")}});
}

bool insideBox(const Eigen::Vector3f& p, const Eigen::Vector3f& centre, float half) {
  return ((p - centre).cwiseAbs().array() < half).all();
}

TEST_F(ProbeValidity, ProbeInARoomIsValid) {
  GltfBuilder gltf;
  gltf.node({{"mesh", boxMesh(gltf, Eigen::Vector3f::Zero(), 1.0f, false)}});
  const Scene scene = loadGltf(gltf.write(dir_, "room"));
  const RayTracer tracer(scene);
  const ProbePlacement placement = place(tracer, Eigen::Vector3f::Zero(), 2.0f);
  EXPECT_EQ(placement.state, ProbeState::Valid);
  EXPECT_EQ(placement.backfaceRatio, 0.0f);
  EXPECT_EQ(placement.offset, Eigen::Vector3f::Zero());
  EXPECT_EQ(raysTraced_, options_.rays);
}

TEST_F(ProbeValidity, ProbeInASolidFarFromItsFacesIsInvalid) {
  GltfBuilder gltf;
  gltf.node({{"mesh", boxMesh(gltf, Eigen::Vector3f::Zero(), 1.0f, true)}});
  const Scene scene = loadGltf(gltf.write(dir_, "solid"));
  const RayTracer tracer(scene);
  // Every face is a whole spacing away, beyond the 0.45 spacing a probe may move.
  const ProbePlacement placement = place(tracer, Eigen::Vector3f::Zero(), 1.0f);
  EXPECT_EQ(placement.state, ProbeState::Invalid);
  EXPECT_EQ(placement.backfaceRatio, 1.0f);
  EXPECT_EQ(placement.offset, Eigen::Vector3f::Zero());
  EXPECT_EQ(raysTraced_, options_.rays) << "no face is near enough to be worth a re-test";
}

TEST_F(ProbeValidity, ProbeJustInsideASolidMovesOutThroughTheNearestFace) {
  GltfBuilder gltf;
  gltf.node({{"mesh", boxMesh(gltf, Eigen::Vector3f::Zero(), 1.0f, true)}});
  const Scene scene = loadGltf(gltf.write(dir_, "solid"));
  const RayTracer tracer(scene);
  const Eigen::Vector3f gridPosition(0.9f, 0.0f, 0.0f);
  const ProbePlacement placement = place(tracer, gridPosition, 1.0f);
  EXPECT_EQ(placement.state, ProbeState::Relocated);
  EXPECT_EQ(placement.backfaceRatio, 1.0f);
  EXPECT_GT(placement.offset.x(), 0.1f) << "out through the +X face, 0.1 away";
  EXPECT_LE(placement.offset.norm(), options_.maxOffsetFraction * 1.0f);
  const Eigen::Vector3f moved = gridPosition + placement.offset;
  EXPECT_FALSE(insideBox(moved, Eigen::Vector3f::Zero(), 1.0f)) << moved.transpose();
  EXPECT_LE(raysTraced_, 10 * options_.rays) << "one test, at most 8 re-tests, one occlusion ray per back-face hit";

  std::int64_t ignored = 0;
  const ProbePlacement there = placeProbe(tracer, moved, 1.0f, directions_, options_, &ignored);
  EXPECT_EQ(there.state, ProbeState::Valid);
}

TEST_F(ProbeValidity, ProbeOutsideASolidIsValid) {
  GltfBuilder gltf;
  gltf.node({{"mesh", boxMesh(gltf, Eigen::Vector3f::Zero(), 1.0f, true)}});
  const Scene scene = loadGltf(gltf.write(dir_, "solid"));
  const RayTracer tracer(scene);
  const ProbePlacement placement = place(tracer, Eigen::Vector3f(3.0f, 0.5f, 0.0f), 1.0f);
  EXPECT_EQ(placement.state, ProbeState::Valid);
  EXPECT_EQ(placement.backfaceRatio, 0.0f);
}

// A panel 0.01 outside the solid's +X face: the 0.02-spacing margin past that face would carry
// the probe through it, and a probe left between the two sees the panel's back.
TEST_F(ProbeValidity, ProbeIsNotMovedThroughASecondSurface) {
  GltfBuilder gltf;
  gltf.node({{"mesh", boxMesh(gltf, Eigen::Vector3f::Zero(), 1.0f, true)}});
  gltf.node({{"mesh", wallFacingPlusX(gltf, 1.01f)}});
  const Scene scene = loadGltf(gltf.write(dir_, "panel"));
  const RayTracer tracer(scene);
  const ProbePlacement placement = place(tracer, Eigen::Vector3f(0.9f, 0.0f, 0.0f), 1.0f);
  EXPECT_EQ(placement.state, ProbeState::Invalid);
  EXPECT_EQ(placement.offset, Eigen::Vector3f::Zero());
}

TEST_F(ProbeValidity, RelocationWorksAtAnyScaleAndDistanceFromTheOrigin) {
  struct Case {
    Eigen::Vector3f centre;
    float half;  // also the spacing
  };
  for (const Case& c : {Case{Eigen::Vector3f::Zero(), 1e-3f}, Case{Eigen::Vector3f::Zero(), 1e5f},
                        Case{Eigen::Vector3f(1e5f, -1e5f, 1e5f), 1.0f}, Case{Eigen::Vector3f(1e4f, 0, 0), 0.5f}}) {
    SCOPED_TRACE(::testing::Message() << "centre " << c.centre.transpose() << ", half size " << c.half);
    GltfBuilder gltf;
    gltf.node({{"mesh", boxMesh(gltf, c.centre, c.half, true)}});
    const Scene scene = loadGltf(gltf.write(dir_, "solid"));
    const RayTracer tracer(scene);
    const float spacing = c.half;
    const Eigen::Vector3f gridPosition = c.centre + Eigen::Vector3f(0.0f, 0.0f, -0.9f * c.half);
    const ProbePlacement placement = place(tracer, gridPosition, spacing);
    EXPECT_EQ(placement.state, ProbeState::Relocated);
    EXPECT_TRUE(placement.offset.allFinite());
    EXPECT_LE(placement.offset.norm(), options_.maxOffsetFraction * spacing);
    EXPECT_FALSE(insideBox(gridPosition + placement.offset, c.centre, c.half));
    EXPECT_EQ(place(tracer, c.centre, spacing).state, ProbeState::Invalid);
    EXPECT_EQ(place(tracer, c.centre + Eigen::Vector3f(0.0f, 2.0f * c.half, 0.0f), spacing).state,
              ProbeState::Valid);
  }
}

TEST_F(ProbeValidity, ProbeInAnEmptySceneIsValid) {
  GltfBuilder gltf;
  const Scene scene = loadGltf(gltf.write(dir_, "empty"));
  const RayTracer tracer(scene);
  const ProbePlacement placement = place(tracer, Eigen::Vector3f(1.0f, 2.0f, 3.0f), 1.0f);
  EXPECT_EQ(placement.state, ProbeState::Valid);
  EXPECT_EQ(placement.backfaceRatio, 0.0f);
}

ProbeGrid gridOf(int x, int y, int z) {
  ProbeGrid grid;
  grid.dims = Eigen::Vector3i(x, y, z);
  return grid;
}

constexpr float kGarbage = std::numeric_limits<float>::quiet_NaN();

TEST(ProbeValidityFill, InvalidProbeGetsTheMeanOfItsValidFaceNeighbours) {
  const ProbeGrid grid = gridOf(3, 3, 1);
  std::vector<ProbeState> states(9, ProbeState::Valid);
  states[grid.linearIndex(1, 1, 0)] = ProbeState::Invalid;
  states[grid.linearIndex(2, 1, 0)] = ProbeState::Relocated;  // a moved probe is as good as a valid one
  std::vector<float> values;
  for (int p = 0; p < 9; ++p) values.insert(values.end(), {float(p), 10.0f * p});
  values[2 * grid.linearIndex(1, 1, 0)] = values[2 * grid.linearIndex(1, 1, 0) + 1] = kGarbage;
  const std::vector<float> before = values;
  fillInvalidProbes(grid, states, 2, values);
  // Face neighbours 1, 3, 5, 7; the corners do not count.
  EXPECT_FLOAT_EQ(values[2 * 4], (1 + 3 + 5 + 7) / 4.0f);
  EXPECT_FLOAT_EQ(values[2 * 4 + 1], 10.0f * (1 + 3 + 5 + 7) / 4.0f);
  for (int p = 0; p < 9; ++p)
    if (p != 4) EXPECT_EQ(values[2 * p], before[2 * p]) << "valid probe " << p << " is untouched";
}

TEST(ProbeValidityFill, EachPassReadsOnlyWhatEarlierPassesFilled) {
  // Valid at both ends: pass 1 fills 1 and 3 from their ends, pass 2 fills 2 from those two.
  const ProbeGrid grid = gridOf(5, 1, 1);
  const std::vector<ProbeState> states = {ProbeState::Valid, ProbeState::Invalid, ProbeState::Invalid,
                                          ProbeState::Invalid, ProbeState::Valid};
  std::vector<float> values = {1.0f, kGarbage, kGarbage, kGarbage, 5.0f};
  fillInvalidProbes(grid, states, 1, values);
  EXPECT_EQ(values, (std::vector<float>{1.0f, 1.0f, 3.0f, 5.0f, 5.0f}));
}

TEST(ProbeValidityFill, GridWithoutValidProbesIsLeftAtZero) {
  const ProbeGrid grid = gridOf(2, 3, 2);
  const std::vector<ProbeState> states(12, ProbeState::Invalid);
  std::vector<float> values(12 * 3, kGarbage);
  fillInvalidProbes(grid, states, 3, values);
  for (const float v : values) EXPECT_EQ(v, 0.0f);
}

TEST(ProbeValidityFill, SingleProbeGrid) {
  const ProbeGrid grid = gridOf(1, 1, 1);
  std::vector<float> values = {0.5f, 2.0f};
  fillInvalidProbes(grid, {ProbeState::Valid}, 2, values);
  EXPECT_EQ(values, (std::vector<float>{0.5f, 2.0f}));
  fillInvalidProbes(grid, {ProbeState::Invalid}, 2, values);
  EXPECT_EQ(values, (std::vector<float>{0.0f, 0.0f}));
}

TEST(ProbeValidityFill, MismatchedSizesAreRejected) {
  const ProbeGrid grid = gridOf(2, 1, 1);
  std::vector<float> values(3);
  EXPECT_THROW(fillInvalidProbes(grid, {ProbeState::Valid, ProbeState::Invalid}, 2, values), std::invalid_argument);
}

}  // namespace
}  // namespace baker
