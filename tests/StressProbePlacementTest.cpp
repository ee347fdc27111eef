// Probes where a grid can put them by accident: exactly on a surface, exactly on the edge
// where two surfaces meet, inside a closed object. Each is asserted to give what a user would
// want: the first two are moved a hair's breadth into the room and bake as a probe there does
// (seeing no sky through the surface they sat on); the third is filled from its neighbours, or
// moved out when it is near enough to a face.
#include <gtest/gtest.h>

#include "bake/Baker.h"
#include "basis/BasisRegistry.h"
#include "scene/GltfLoader.h"
#include "scene/RayTracer.h"
#include "tests/TestData.h"
#include "tests/TransportTestSupport.h"

namespace baker {
namespace {

// default_room (open towards +Z) under a bright sky, so that a ray leaking through the floor or
// a wall would bring light that cannot arrive otherwise. Its tall box is the closed object:
// x −1.3..−0.3, y 0..2, z 0.8..1.8, standing on the floor.
class StressProbePlacement : public ::testing::Test {
 protected:
  void SetUp() override {
    SceneOptions options;
    options.sky = "4,4,4";
    room_ = std::make_unique<test::TracedScene>(loadGltf(test::sourcePath("data/default_room/default_room.gltf"), options));
    basis_ = makeBasis("sh-l2");
    settings_.rays = 512;
    settings_.transport.bounces = 1;
  }

  // A grid of `dims` probes `spacing` apart from `first`, baked as a whole.
  Volume bakeGrid(const Eigen::Vector3d& first, const Eigen::Vector3i& dims, double spacing) const {
    ProbeGrid grid;
    grid.dims = dims;
    grid.origin = first;
    grid.spacing = spacing;
    return bakeVolume(room_->scene(), room_->tracer(), *basis_, grid, settings_, nullptr);
  }

  // Rays of a probe at `position` that head into `side` (by more than 0.1 of their length)
  // and escape to the sky.
  int escapingTowards(const Eigen::Vector3f& position, const Eigen::Vector3f& side) const {
    const test::BakedProbe probe = test::bakeProbe(room_->scene(), room_->tracer(), *basis_, settings_, position);
    int escaping = 0;
    for (std::size_t r = 0; r < probe.samples.directions.size(); ++r)
      escaping += probe.samples.directions[r].dot(side) > 0.1f && probe.samples.visibility[r] > 0.0f;
    return escaping;
  }

  // E for the six axis normals of probe 0 of `volume`.
  std::vector<Eigen::Vector3f> axisIrradiance(const Volume& volume) const {
    std::vector<Eigen::Vector3f> e;
    for (int axis = 0; axis < 3; ++axis)
      for (double sign : {1.0, -1.0}) e.push_back(basis_->reconstruct(volume.probe(0), sign * Eigen::Vector3d::Unit(axis)));
    return e;
  }

  // Within the noise of 512 paths (a leak of sky shows as several times the whole value).
  void expectSameIrradiance(const Volume& onSurface, const Volume& inside) const {
    const std::vector<Eigen::Vector3f> a = axisIrradiance(onSurface), b = axisIrradiance(inside);
    float largest = 0.0f;
    for (const Eigen::Vector3f& e : b) largest = std::max(largest, e.maxCoeff());
    for (std::size_t k = 0; k < a.size(); ++k)
      EXPECT_LT((a[k] - b[k]).cwiseAbs().maxCoeff(), 0.1f * largest) << "axis normal " << k;
  }

  std::unique_ptr<test::TracedScene> room_;
  std::unique_ptr<Basis> basis_;
  BakeSettings settings_;
};

// Its rays into the floor would start on it and see the sky below; instead half of its test rays
// meet the floor's back face at distance 0, so it is moved off, a hundredth of a spacing.
TEST_F(StressProbePlacement, AProbeExactlyOnTheFloorIsMovedJustAboveIt) {
  const Eigen::Vector3f onFloor(1.0f, 0.0f, 3.0f);
  const Volume on = bakeGrid(onFloor.cast<double>(), {1, 1, 1}, 0.5);
  ASSERT_EQ(on.states[0], ProbeState::Relocated);
  EXPECT_GT(on.offsets[0].y(), 0.0f);
  EXPECT_LT(on.offsets[0].norm(), 0.05f * 0.5f);
  EXPECT_EQ(escapingTowards(onFloor + on.offsets[0], -Eigen::Vector3f::UnitY()), 0) << "the sky leaks through the floor";
  expectSameIrradiance(on, bakeGrid({1.0, 1e-3, 3.0}, {1, 1, 1}, 0.5));
}

TEST_F(StressProbePlacement, AProbeExactlyOnAnEdgeIsMovedJustInsideTheRoom) {
  const Eigen::Vector3f onEdge(-2.0f, 0.0f, 3.0f);  // where the floor meets the red wall
  const Volume on = bakeGrid(onEdge.cast<double>(), {1, 1, 1}, 0.5);
  ASSERT_EQ(on.states[0], ProbeState::Relocated);
  EXPECT_GT(on.offsets[0].x(), 0.0f);
  EXPECT_GT(on.offsets[0].y(), 0.0f);
  EXPECT_LT(on.offsets[0].norm(), 0.05f * 0.5f);
  const Eigen::Vector3f baked = onEdge + on.offsets[0];
  EXPECT_EQ(escapingTowards(baked, -Eigen::Vector3f::UnitY()), 0) << "the sky leaks through the floor";
  EXPECT_EQ(escapingTowards(baked, -Eigen::Vector3f::UnitX()), 0) << "the sky leaks through the wall";
  expectSameIrradiance(on, bakeGrid({-2.0 + 1e-3, 1e-3, 3.0}, {1, 1, 1}, 0.5));
}

// Half a metre from every face of the box is more than a probe 1 m from its neighbours may
// move (0.45 m): it is filled with the mean of its two neighbours, which stand outside.
TEST_F(StressProbePlacement, AProbeDeepInsideAClosedObjectTakesItsNeighboursMean) {
  const Volume row = bakeGrid({-1.8, 1.0, 1.3}, {3, 1, 1}, 1.0);
  ASSERT_EQ(row.states[0], ProbeState::Valid);
  ASSERT_EQ(row.states[2], ProbeState::Valid);
  EXPECT_EQ(row.states[1], ProbeState::Invalid);
  for (int i = 0; i < row.coefficientsPerProbe; ++i)
    EXPECT_FLOAT_EQ(row.probe(1)[i], 0.5f * (row.probe(0)[i] + row.probe(2)[i])) << i;
}

// A tenth of a metre inside the box's +X face, it is moved out through that face.
TEST_F(StressProbePlacement, AProbeJustInsideAClosedObjectIsMovedOutOfIt) {
  const Volume moved = bakeGrid({-0.4, 1.0, 1.3}, {1, 1, 1}, 1.0);
  ASSERT_EQ(moved.states[0], ProbeState::Relocated);
  const Eigen::Vector3f baked = Eigen::Vector3f(-0.4f, 1.0f, 1.3f) + moved.offsets[0];
  EXPECT_GT(baked.x(), -0.3f) << "still inside the box";
  EXPECT_LE(moved.offsets[0].norm(), 0.45f);
  EXPECT_GT(moved.offsets[0].x(), 0.0f);
}

}  // namespace
}  // namespace baker
