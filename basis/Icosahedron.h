#pragma once
#include <Eigen/Core>
#include <array>

namespace baker {

// Which barycentric coordinates a function on the icosahedron's triangles is built on.
// Spherical: b = M⁻¹d with M = [v̂0 v̂1 v̂2]; they are homogeneous of degree 1 in d and do not
// sum to 1 (1.258 at a face centre). Flat: b/(b0 + b1 + b2), the planar barycentrics of the
// point where d meets the flat face.
enum class Barycentrics { Spherical, Flat };
// "spherical" or "flat", as volume files name them.
const char* barycentricsName(Barycentrics kind);

// A direction located in one triangle of the icosahedron.
struct TrianglePoint {
  int triangle = 0;
  std::array<int, 3> vertices{};  // the triangle's vertices, in Icosahedron::triangle() order
  Eigen::Vector3d spherical;      // w.r.t. those vertices, in that order
  Eigen::Vector3d flat;

  const Eigen::Vector3d& barycentrics(Barycentrics kind) const {
    return kind == Barycentrics::Spherical ? spherical : flat;
  }
};

// The regular icosahedron inscribed in the unit sphere, indexed as in Iwanicki & Sloan,
// "Ambient Dice" (2017), §2.2. With Φ = 1/golden ratio the vertices are, before normalising,
//   group A (±1, ±Φ, 0): 0–3,   group B (0, ±1, ±Φ): 4–7,   group C (±Φ, 0, ±1): 8–11,
// and within a group the sign bits of the two non-zero coordinates, first one lowest, give
// the offset: (−Φ, 0, 1) is 9. Vertex i ^ 3 is the antipode of vertex i.
//
// Triangles 0–7 are the "base" triangles, one inside each octant, indexed by the octant's
// sign bits (x lowest); 8–11 (red), 12–15 (green) and 16–19 (blue) are the side triangles
// crossing the x = 0, y = 0 and z = 0 planes, indexed by the signs of the other two
// coordinates (y,z), (x,z) and (x,y). Every triangle lists its vertices counter-clockwise
// seen from outside, starting with its lowest vertex index, so an edge shared by two
// triangles appears in opposite orders in them.
class Icosahedron {
 public:
  static constexpr int kVertexCount = 12;
  static constexpr int kTriangleCount = 20;
  static constexpr double kPhiInverse = 0.61803398874989484820;  // Φ = (√5 − 1)/2

  static const Icosahedron& instance();

  const Eigen::Vector3d& vertex(int i) const { return vertices_[i]; }
  const std::array<int, 3>& triangle(int t) const { return triangles_[t]; }

  // An orthonormal tangent frame at each vertex, right-handed with the normal: t × b = v̂.
  // t is the coordinate axis in which the vertex has a zero coordinate (z for group A, x for
  // B, y for C) and b = v̂ × t. Any frame spans the same functions; this one maps onto itself,
  // up to signs, under the coordinate mirrors that the vertex indexing is built on.
  const Eigen::Vector3d& tangent(int i) const { return tangents_[i]; }
  const Eigen::Vector3d& bitangent(int i) const { return bitangents_[i]; }

  // The triangle containing the unit vector d, found without search (see Icosahedron.cpp).
  // On an edge or at a vertex it is one of the triangles that contain d.
  TrianglePoint locate(const Eigen::Vector3d& d) const;
  // d expressed in triangle t, whether or not t contains it (barycentrics then go negative).
  TrianglePoint inTriangle(int t, const Eigen::Vector3d& d) const;

 private:
  Icosahedron();

  std::array<Eigen::Vector3d, kVertexCount> vertices_;
  std::array<Eigen::Vector3d, kVertexCount> tangents_;
  std::array<Eigen::Vector3d, kVertexCount> bitangents_;
  std::array<std::array<int, 3>, kTriangleCount> triangles_;
  std::array<Eigen::Matrix3d, kTriangleCount> inverse_;  // [v̂0 v̂1 v̂2]⁻¹ per triangle
};

}  // namespace baker
