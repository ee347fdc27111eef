#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <sstream>
#include <utility>
#include <vector>

#include "basis/Icosahedron.h"
#include "tests/RandomDirection.h"

namespace baker {
namespace {

const Icosahedron& ico() { return Icosahedron::instance(); }

using test::randomDirection;

TEST(Icosahedron, VerticesFollowThePapersIndexing) {
  const double phi = (std::sqrt(5.0) - 1.0) / 2.0;
  EXPECT_NEAR(Icosahedron::kPhiInverse, phi, 1e-16);
  // The paper's example: (−Φ, 0, 1) is group C with sign bits 1 (x, the low bit) and 0 (z).
  EXPECT_LT((ico().vertex(9) - Eigen::Vector3d(-phi, 0.0, 1.0).normalized()).norm(), 1e-15);
  for (int i = 0; i < 12; ++i) {
    const double s1 = (i & 1) ? -1 : 1, s2 = (i & 2) ? -1 : 1;
    const Eigen::Vector3d raw[3] = {{s1, s2 * phi, 0}, {0, s1, s2 * phi}, {s1 * phi, 0, s2}};
    EXPECT_LT((ico().vertex(i) - raw[i / 4].normalized()).norm(), 1e-15) << "vertex " << i;
    EXPECT_NEAR(ico().vertex(i).norm(), 1.0, 1e-15);
    EXPECT_LT((ico().vertex(i ^ 3) + ico().vertex(i)).norm(), 1e-15) << "antipode of " << i;
  }
}

TEST(Icosahedron, TrianglesAreTheTwentyFacesInTheDocumentedOrder) {
  const double edgeCosine = 1.0 / std::sqrt(5.0);  // neighbouring vertices are 63.4° apart
  std::map<std::pair<int, int>, int> directedEdges;
  for (int t = 0; t < 20; ++t) {
    const std::array<int, 3>& tri = ico().triangle(t);
    EXPECT_LT(tri[0], tri[1]) << "triangle " << t << " must start at its lowest vertex";
    EXPECT_LT(tri[0], tri[2]) << "triangle " << t;
    const Eigen::Vector3d& a = ico().vertex(tri[0]);
    const Eigen::Vector3d& b = ico().vertex(tri[1]);
    const Eigen::Vector3d& c = ico().vertex(tri[2]);
    EXPECT_GT(a.dot(b.cross(c)), 0.0) << "triangle " << t << " must be counter-clockwise from outside";
    EXPECT_NEAR(a.dot(b), edgeCosine, 1e-15);
    EXPECT_NEAR(b.dot(c), edgeCosine, 1e-15);
    EXPECT_NEAR(c.dot(a), edgeCosine, 1e-15);
    for (int k = 0; k < 3; ++k) ++directedEdges[{tri[k], tri[(k + 1) % 3]}];

    // Where the paper puts each triangle: base ones inside their octant, side ones across
    // the plane of their colour, in the quadrant given by their index bits.
    const Eigen::Vector3d centre = (a + b + c) / 3.0;
    const auto sign = [](int bit) { return bit ? -1.0 : 1.0; };
    if (t < 8) {
      for (int axis = 0; axis < 3; ++axis) EXPECT_GT(centre[axis] * sign((t >> axis) & 1), 0.0) << "triangle " << t;
    } else {
      const int plane = (t - 8) / 4, bits = (t - 8) % 4;
      const int first = plane == 0 ? 1 : 0, second = plane == 2 ? 1 : 2;
      EXPECT_NEAR(centre[plane], 0.0, 1e-15) << "triangle " << t;
      EXPECT_GT(centre[first] * sign(bits & 1), 0.0) << "triangle " << t;
      EXPECT_GT(centre[second] * sign(bits >> 1), 0.0) << "triangle " << t;
    }
  }
  // A closed, consistently oriented surface: 30 edges, each used once in each direction.
  EXPECT_EQ(directedEdges.size(), 60u);
  for (const auto& [edge, uses] : directedEdges) {
    EXPECT_EQ(uses, 1);
    EXPECT_EQ(directedEdges.count({edge.second, edge.first}), 1u);
  }
}

TEST(Icosahedron, TangentFramesAreOrthonormalAndRightHanded) {
  for (int i = 0; i < 12; ++i) {
    const Eigen::Vector3d &v = ico().vertex(i), &t = ico().tangent(i), &b = ico().bitangent(i);
    EXPECT_NEAR(t.norm(), 1.0, 1e-15);
    EXPECT_NEAR(b.norm(), 1.0, 1e-15);
    EXPECT_NEAR(t.dot(v), 0.0, 1e-15);
    EXPECT_NEAR(b.dot(v), 0.0, 1e-15);
    EXPECT_NEAR(t.dot(b), 0.0, 1e-15);
    EXPECT_LT((t.cross(b) - v).norm(), 1e-15) << "vertex " << i;
  }
}

TEST(Icosahedron, SphericalBarycentricsSumTo1258AtAFaceCentre) {
  // At the centre all three are 1/|v0 + v1 + v2| = 1/√(3 + 6/√5).
  const double expected = 3.0 / std::sqrt(3.0 + 6.0 / std::sqrt(5.0));
  EXPECT_NEAR(expected, 1.258, 1e-3);
  for (int t = 0; t < 20; ++t) {
    const std::array<int, 3>& tri = ico().triangle(t);
    const Eigen::Vector3d centre = (ico().vertex(tri[0]) + ico().vertex(tri[1]) + ico().vertex(tri[2])).normalized();
    const TrianglePoint p = ico().locate(centre);
    EXPECT_EQ(p.triangle, t);
    EXPECT_NEAR(p.spherical.sum(), expected, 1e-14);
    EXPECT_NEAR(p.spherical.maxCoeff() - p.spherical.minCoeff(), 0.0, 1e-14);
    EXPECT_LT((p.flat - Eigen::Vector3d::Constant(1.0 / 3.0)).norm(), 1e-14);
  }
}

// The branch-free lookup against a search of all 20 triangles, over random directions and the
// places where it could go wrong: vertices, edges (on them and just off them on both sides)
// and the coordinate planes where the octant changes.
TEST(Icosahedron, LookupAgreesWithBruteForceSearch) {
  std::mt19937_64 rng(20170626);
  std::vector<Eigen::Vector3d> directions;
  for (int k = 0; k < 1000000; ++k) directions.push_back(randomDirection(rng));
  const double offsets[] = {1e-6, 1e-9, 1e-12, 1e-15};
  for (int i = 0; i < 12; ++i) {
    directions.push_back(ico().vertex(i));
    for (double offset : offsets)
      for (int k = 0; k < 20; ++k) directions.push_back((ico().vertex(i) + offset * randomDirection(rng)).normalized());
  }
  int edgeCount = 0;
  for (int i = 0; i < 12; ++i)
    for (int j = i + 1; j < 12; ++j) {
      const Eigen::Vector3d &a = ico().vertex(i), &b = ico().vertex(j);
      if (a.dot(b) < 0.4) continue;  // not neighbours
      ++edgeCount;
      const Eigen::Vector3d normal = a.cross(b).normalized();
      const Eigen::Vector3d along = normal.cross(a);  // unit tangent at a towards b
      const double length = std::acos(a.dot(b));
      for (int k = 0; k <= 1000; ++k) {
        const double s = length * k / 1000.0;
        const Eigen::Vector3d onEdge = std::cos(s) * a + std::sin(s) * along;
        directions.push_back(onEdge);
        for (double offset : offsets) {
          directions.push_back((onEdge + offset * normal).normalized());
          directions.push_back((onEdge - offset * normal).normalized());
        }
      }
    }
  ASSERT_EQ(edgeCount, 30);
  for (int axis = 0; axis < 3; ++axis) {
    for (double sign : {1.0, -1.0}) directions.push_back(sign * Eigen::Vector3d::Unit(axis));
    for (int k = 0; k < 20000; ++k) {
      Eigen::Vector3d d = randomDirection(rng);
      d[axis] = k % 2 ? 0.0 : -0.0;
      directions.push_back(d.normalized());
    }
  }

  int failures = 0;
  std::ostringstream first;
  for (const Eigen::Vector3d& d : directions) {
    std::vector<int> containing;
    for (int t = 0; t < 20; ++t)
      if (ico().inTriangle(t, d).spherical.minCoeff() >= -1e-12) containing.push_back(t);
    const TrianglePoint p = ico().locate(d);
    const bool found = std::find(containing.begin(), containing.end(), p.triangle) != containing.end();
    const bool consistent = p.vertices == ico().triangle(p.triangle) &&
                            (p.spherical - ico().inTriangle(p.triangle, d).spherical).norm() == 0.0 &&
                            std::abs(p.flat.sum() - 1.0) < 1e-15 && (p.flat * p.spherical.sum() - p.spherical).norm() < 1e-15;
    if (containing.empty() || !found || p.spherical.minCoeff() < -1e-9 || !consistent) {
      if (failures++ == 0)
        first << "direction " << d.transpose() << ": lookup gave triangle " << p.triangle << " with barycentrics "
              << p.spherical.transpose() << ", brute force found " << containing.size() << " triangle(s)";
    }
  }
  EXPECT_GE(directions.size(), 1000000u);
  EXPECT_EQ(failures, 0) << first.str();
}

}  // namespace
}  // namespace baker
