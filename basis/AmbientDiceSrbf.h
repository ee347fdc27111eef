#pragma once
#include <string>
#include <utility>
#include <vector>

#include "basis/Basis.h"

namespace baker {

// Twelve hemispherical lobes on the icosahedron's vertices, λ(v̂·d) with
//   λ(c) = s · (cos2Weight · max(0, c)² + cos4Weight · max(0, c)⁴),
// s chosen so the lobes sum to 1 everywhere. That is possible because, for every unit d, the
// clamped powers sum to constants: one of each antipodal pair is positive, and the vertices
// form a spherical 5-design, so Σ over all 12 of (v̂·d)² = 12·⅓ and of (v̂·d)⁴ = 12·⅕; halved,
// Σ max(0, v̂·d)² = 2 and Σ max(0, v̂·d)⁴ = 6/5. Hence ½cos² and ⅚cos⁴ lobes are partitions of
// unity, and so is any mix.
class AmbientDiceSrbfFunctions : public SphericalFunctions {
 public:
  AmbientDiceSrbfFunctions(double cos2Weight, double cos4Weight);
  int count() const override { return 12; }
  void evaluate(const Eigen::Vector3d& direction, double* values) const override;
  nlohmann::json describe() const override;
  // One plane v̂·d = 0 per antipodal pair of vertices: both lobes of the pair kink on it.
  std::vector<Eigen::Vector3d> kinkPlanes() const override;
  std::optional<RadialLobes> radialLobes() const override;
  // λ(c) for c ≥ 0.
  double lobe(double cosine) const;
  // The coefficients of c² and c⁴ in λ, normalisation included.
  double cos2Coefficient() const { return cos2_; }
  double cos4Coefficient() const { return cos4_; }

 private:
  double cos2_, cos4_;  // coefficients of c² and c⁴ in λ, normalisation included
};

// Ambient Dice SRBF: per channel the coefficient of the lobe on vertex i (icosahedron
// indexing). Reconstruction reads the 6 lobes whose vertices face d, 18 of the 36 numbers.
// CLI names: "ad-cos2", lobes ½cos²; "ad-srbf", the paper's 0.7·cos² + 0.3·cos⁴ of the raw
// clamped powers, i.e. (35/44)·½cos² + (9/44)·⅚cos⁴.
class AmbientDiceSrbf : public Basis {
 public:
  AmbientDiceSrbf(std::string name, double cos2Weight, double cos4Weight)
      : name_(std::move(name)), functions_(cos2Weight, cos4Weight) {}
  std::string name() const override { return name_; }
  std::string family() const override { return "ambient-dice"; }
  const SphericalFunctions& functions(int) const override { return functions_; }
  int coefficientsPerLookup() const override { return 18; }
  Eigen::Vector3f reconstruct(const float* coefficients, const Eigen::Vector3d& d) const override;

 private:
  std::string name_;
  AmbientDiceSrbfFunctions functions_;
};

}  // namespace baker
