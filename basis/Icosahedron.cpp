#include "basis/Icosahedron.h"

#include <Eigen/Dense>
#include <algorithm>
#include <utility>

namespace baker {
namespace {

constexpr double kPhi = Icosahedron::kPhiInverse;
constexpr double kPhi2 = 1.0 - kPhi;  // Φ² + Φ = 1

// Indices of the vertices of groups A, B and C whose signs are those of the octant (sign bits
// sx, sy, sz), and of the vertex that replaces each across the opposite edge of the octant's
// base triangle: the next group round (A → C, B → A, C → B) with the sign of its Φ
// coordinate flipped.
struct OctantVertices {
  int a, b, c, aFlipped, bFlipped, cFlipped;
};

OctantVertices octantVertices(int sx, int sy, int sz) {
  return {sx + 2 * sy, 4 + sy + 2 * sz, 8 + sx + 2 * sz, 8 + (1 - sx) + 2 * sz, sx + 2 * (1 - sy), 4 + sy + 2 * (1 - sz)};
}

}  // namespace

const Icosahedron& Icosahedron::instance() {
  static const Icosahedron icosahedron;
  return icosahedron;
}

Icosahedron::Icosahedron() {
  for (int i = 0; i < kVertexCount; ++i) {
    const double first = (i & 1) ? -1.0 : 1.0, second = (i & 2) ? -1.0 : 1.0;
    Eigen::Vector3d v, axis;
    switch (i / 4) {
      case 0: v = {first, second * kPhi, 0.0}, axis = Eigen::Vector3d::UnitZ(); break;
      case 1: v = {0.0, first, second * kPhi}, axis = Eigen::Vector3d::UnitX(); break;
      default: v = {first * kPhi, 0.0, second}, axis = Eigen::Vector3d::UnitY(); break;
    }
    vertices_[i] = v.normalized();
    tangents_[i] = axis;
    bitangents_[i] = vertices_[i].cross(axis);
  }

  // Every triangle is met from the octants it touches (a side triangle from two); the
  // canonical vertex order makes those meetings agree.
  for (int octant = 0; octant < 8; ++octant) {
    const int sx = octant & 1, sy = (octant >> 1) & 1, sz = octant >> 2;
    const OctantVertices o = octantVertices(sx, sy, sz);
    const std::array<std::pair<int, std::array<int, 3>>, 4> found = {{
        {octant, {o.a, o.b, o.c}},
        {8 + sy + 2 * sz, {o.aFlipped, o.b, o.c}},
        {12 + sx + 2 * sz, {o.a, o.bFlipped, o.c}},
        {16 + sx + 2 * sy, {o.a, o.b, o.cFlipped}},
    }};
    for (auto [t, tri] : found) {
      std::rotate(tri.begin(), std::min_element(tri.begin(), tri.end()), tri.end());
      if (vertices_[tri[0]].dot(vertices_[tri[1]].cross(vertices_[tri[2]])) < 0) std::swap(tri[1], tri[2]);
      triangles_[t] = tri;
    }
  }

  for (int t = 0; t < kTriangleCount; ++t) {
    Eigen::Matrix3d m;
    for (int k = 0; k < 3; ++k) m.col(k) = vertices_[triangles_[t][k]];
    inverse_[t] = m.inverse();
  }
}

// Iwanicki & Sloan's lookup (their Listing 1, with the vertex order taken from the triangle
// table instead). The octant's sign bits name its base triangle; the rest of the octant is
// covered by halves of the three side triangles beyond the base triangle's edges. Mirroring
// d into the (+,+,+) octant, three dot products with the normals of the planes through the
// origin and those edges tell which, if any, of the three d lies beyond. The half triangles
// are disjoint, so at most one test fails except at a vertex, where any choice is right.
TrianglePoint Icosahedron::locate(const Eigen::Vector3d& d) const {
  const int sx = d.x() < 0.0, sy = d.y() < 0.0, sz = d.z() < 0.0;
  const Eigen::Vector3d a = d.cwiseAbs();
  // Normals B × C, C × A and A × B of the base triangle A = (1, Φ, 0), B = (0, 1, Φ),
  // C = (Φ, 0, 1): each test is positive on the base triangle's side of the edge.
  const bool keepA = a.x() + kPhi2 * a.y() - kPhi * a.z() > 0.0;
  const bool keepB = -kPhi * a.x() + a.y() + kPhi2 * a.z() > 0.0;
  const bool keepC = kPhi2 * a.x() - kPhi * a.y() + a.z() > 0.0;
  int t = sx + 2 * sy + 4 * sz;
  t = keepA ? t : 8 + sy + 2 * sz;
  t = keepB ? t : 12 + sx + 2 * sz;
  t = keepC ? t : 16 + sx + 2 * sy;
  return inTriangle(t, d);
}

TrianglePoint Icosahedron::inTriangle(int t, const Eigen::Vector3d& d) const {
  TrianglePoint p;
  p.triangle = t;
  p.vertices = triangles_[t];
  p.spherical = inverse_[t] * d;
  p.flat = p.spherical / p.spherical.sum();
  return p;
}

const char* barycentricsName(Barycentrics kind) { return kind == Barycentrics::Spherical ? "spherical" : "flat"; }

}  // namespace baker
