#pragma once
#include <string>

#include "basis/AmbientDiceBezier.h"
#include "basis/AmbientDiceLinear.h"
#include "basis/Basis.h"

namespace baker {

// Ambient Dice in YCoCg (§2.3.2), CLI name "ad-ycocg": luminance Y as the spherical Bézier
// patch (36 data: value, ∂t, ∂b per vertex, vertex-major), chrominance Co and Cg as one value
// per vertex interpolated linearly in spherical barycentrics (12 each; the reading that
// reproduces the paper's numbers). Stored Y, Co, Cg at offsets 0, 36, 48: 60 numbers, of
// which the 9 + 3 + 3 of the triangle's vertices are read.
class AmbientDiceYCoCg : public Basis {
 public:
  AmbientDiceYCoCg() : luminance_(Barycentrics::Spherical), chrominance_(Barycentrics::Spherical) {}
  std::string name() const override { return "ad-ycocg"; }
  std::string family() const override { return "ambient-dice"; }
  ColorSpace colorSpace() const override { return ColorSpace::YCoCg; }
  // Co and Cg share one function set, so they are projected together.
  const SphericalFunctions& functions(int channel) const override;
  int coefficientsPerLookup() const override { return 15; }
  Eigen::Vector3f reconstruct(const float* coefficients, const Eigen::Vector3d& d) const override;

 private:
  AmbientDiceBezierFunctions luminance_;
  AmbientDiceLinearFunctions chrominance_;
};

}  // namespace baker
