#pragma once
#include <array>
#include <memory>
#include <nlohmann/json.hpp>

#include "basis/Basis.h"

namespace baker {

// Glossy specular from radiance stored in a basis, after the seed post on Ambient Dice for
// radiance: the GGX-weighted mean of the incoming radiance (GgxLobe, F0 = 1),
//   S(n, v, roughness) = ∫ L(ω) ρ(ω) (n·ω)⁺ dω / A,   A = ∫ ρ(ω) (n·ω)⁺ dω,
// is read as a blend of the mirror radiance and the cosine-weighted mean,
//   S ≈ (1 − w) L(r) + w E(n)/π,   r = 2(n·v)n − v,
// with one weight w(roughness, n·v) per basis from a table: mirror at roughness 0 (w = 0),
// diffuse-like at 1. In a basis that holds a constant sky exactly both terms are exact for it,
// so S is too, whatever w. A lobe narrow against the basis's functions gets the blurred
// radiance the basis holds, however good the weight. Dividing
// by A keeps S a radiance: a renderer multiplies by A (given alongside, and by its Fresnel).
//
// Each weight is the least-squares best over the basis's own functions (every function of every
// channel's set), each seen from kFrames normals spread over the sphere at that n·v: so the
// table is what the basis can do, and one table serves every lobe of a lobe basis.
class SpecularBlend {
 public:
  static constexpr int kSteps = 16;   // nodes per axis: roughness j/15 and n·v k/15
  static constexpr int kFrames = 16;  // normals each weight is fitted over

  explicit SpecularBlend(const Basis& basis);

  // w and A, bilinear between the nodes; roughness and n·v are clamped to [0, 1].
  double diffuseWeight(double roughness, double cosView) const { return lookup(weight_, roughness, cosView); }
  double albedo(double roughness, double cosView) const { return lookup(albedo_, roughness, cosView); }
  // The tables and the formula, for a volume's metadata ("baker.specular").
  nlohmann::json describe() const;

 private:
  using Table = std::array<std::array<double, kSteps>, kSteps>;  // [roughness][n·v]
  static double lookup(const Table& table, double roughness, double cosView);
  static double node(int index) { return double(index) / (kSteps - 1); }

  Table weight_{}, albedo_{};
};

// The blend of `basis` (its name and parameters), fitted once per process.
std::shared_ptr<const SpecularBlend> specularBlendOf(const Basis& basis);

}  // namespace baker
