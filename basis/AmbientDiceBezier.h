#pragma once
#include <array>
#include <string>

#include "basis/Basis.h"
#include "basis/Icosahedron.h"

namespace baker {

// Iwanicki & Sloan's hybrid cubic Bézier patch on the icosahedron (Ambient Dice §2.3.1), as 36
// functions per channel. The data are, per vertex i, vertex-major:
//   3i     the value f(v_i),
//   3i + 1 the derivative along the vertex's tangent t (Icosahedron::tangent),
//   3i + 2 the derivative along its bitangent b.
// The patch is linear in the data, so function j is the patch for datum j = 1 and all others
// 0; it is non-zero only on the 5 triangles around its vertex.
//
// On a triangle (v0, v1, v2) with barycentrics b the patch is Σ c_ijk · 3!/(i!j!k!) b0^i b1^j b2^k
// over i + j + k = 3, with control points
//   c300 = f(v0), and cyclically;
//   c210 = vf·f(v0) + (1/(3α))·(e·t ∂t f(v0) + e·b ∂b f(v0)), e the unit tangent at v0 along
//          the great circle towards v1, α = ½√((5 + √5)/2), and likewise for the other five;
//   c111 = Σk wk c111^(k), wk = b_{k+1}b_{k+2} / (b1b2 + b0b2 + b0b1), where c111^(0) =
//          a0(c030 + c003) + a1(c021 + c012) + a2(c120 + c102) makes the patch C1 across the
//          edge opposite v0 and c111^(1), c111^(2) follow cyclically. At a vertex, where the
//          weights are 0/0, that vertex's own weight is 1 (the centre term vanishes there).
// Spherical barycentrics: vf = 1/√5, a0 = (√5 − 5)/40, a1 = (11√5 − 15)/40, a2 = √5/10: C1
// across every edge, but constants are not reproduced (all values 1 gives 0.938 at face
// centres). Flat barycentrics: vf = 1, a0 = −¼, a1 = ¼, a2 = ½: constants are reproduced,
// cross derivatives do not match across edges.
//
// Derivative units. The paper takes (β, α, 0), β = −α/√5, for the spherical barycentrics of
// the unit tangent at v0 along the edge; they are (−½, √5/2, 0) = (β, α, 0)/cos(θ/2), θ =
// arccos(1/√5) the angle of an edge (1/α is the length of a flat edge). With the paper's α, as
// here, the patch's gradient on the sphere at a vertex is the stored gradient divided by
// cos(θ/2) = √((5 + √5)/10) ≈ 0.8507, in both variants. Scaling all derivative data alike
// leaves the span, hence every projection, unchanged; keeping the paper's constant lets an
// engine that evaluates the paper's formula read these coefficients as they are.
class AmbientDiceBezierFunctions : public SphericalFunctions {
 public:
  explicit AmbientDiceBezierFunctions(Barycentrics kind);
  Barycentrics barycentrics() const { return kind_; }
  // vf, (a0, a1, a2) and the paper's α above, for describing the patch to importers.
  double vertexFactor() const { return vertexFactor_; }
  std::array<double, 3> interiorWeights() const { return {a0_, a1_, a2_}; }
  static double alpha();
  int count() const override { return 3 * Icosahedron::kVertexCount; }
  void evaluate(const Eigen::Vector3d& direction, double* values) const override;
  nlohmann::json describe() const override;
  // The weights of the 9 data of p's triangle in the patch at p: datum j of corner k
  // (vertex p.vertices[k]) at index 3k + j.
  void localWeights(const TrianglePoint& p, double* weights) const;

 private:
  Barycentrics kind_;
  double vertexFactor_, a0_, a1_, a2_;  // vf, a0, a1, a2 above
  // Per triangle, per ordered pair of corners (k, m) at index 3k + m: (e·t, e·b)/(3α) for the
  // edge from corner k towards corner m, in the frame of corner k.
  std::array<std::array<Eigen::Vector2d, 9>, Icosahedron::kTriangleCount> edgeFactors_;
};

// Ambient Dice with an RGB Bézier patch per channel: CLI names "ad-rgb" (spherical
// barycentrics) and "ad-rgb-flat" (flat). Channel c holds the 36 data above at offset 36c;
// 108 stored, the 27 of the triangle's three vertices read.
class AmbientDiceBezier : public Basis {
 public:
  explicit AmbientDiceBezier(Barycentrics kind) : functions_(kind) {}
  std::string name() const override;
  std::string family() const override { return "ambient-dice"; }
  const SphericalFunctions& functions(int) const override { return functions_; }
  int coefficientsPerLookup() const override { return 27; }
  Eigen::Vector3f reconstruct(const float* coefficients, const Eigen::Vector3d& d) const override;

 private:
  AmbientDiceBezierFunctions functions_;
};

}  // namespace baker
