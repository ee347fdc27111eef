#pragma once
#include "basis/Basis.h"

namespace baker {

// The six cos² lobes of the ambient cube, max(0, ±a·d)² for a = x, y, z, in the order
// +x, −x, +y, −y, +z, −z. They sum to 1 everywhere, so constants are reproduced.
class AmbientCubeLobes : public SphericalFunctions {
 public:
  int count() const override { return 6; }
  void evaluate(const Eigen::Vector3d& direction, double* values) const override;
  nlohmann::json describe() const override;
  // The lobes kink only on the coordinate planes, which exact quadratures already split on.
  std::vector<Eigen::Vector3d> kinkPlanes() const override { return {}; }
  std::optional<RadialLobes> radialLobes() const override;
};

// The ambient cube: one value per cube face for each RGB channel (18 coefficients). Any
// direction faces at most three of the six lobes, so a lookup reads 9. CLI name "ambient-cube".
class AmbientCubeBasis : public Basis {
 public:
  std::string name() const override { return "ambient-cube"; }
  std::string family() const override { return "ambient-cube"; }
  const SphericalFunctions& functions(int) const override { return lobes_; }
  int coefficientsPerLookup() const override { return 9; }
  Eigen::Vector3f reconstruct(const float* coefficients, const Eigen::Vector3d& d) const override;

 private:
  AmbientCubeLobes lobes_;
};

}  // namespace baker
