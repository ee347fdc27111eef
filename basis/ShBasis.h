#pragma once
#include "basis/Basis.h"
#include "basis/SphericalHarmonics.h"

namespace baker {

// Real spherical harmonics of order L for each RGB channel: (L+1)² coefficients per channel,
// all of them read for any direction. CLI name "sh-lL".
class ShBasis : public Basis {
 public:
  explicit ShBasis(int order) : sh_(order) {}
  std::string name() const override { return "sh-l" + std::to_string(sh_.order()); }
  std::string family() const override { return "sh"; }
  const SphericalFunctions& functions(int) const override { return sh_; }
  int coefficientsPerLookup() const override { return 3 * sh_.count(); }
  Eigen::Vector3f reconstruct(const float* coefficients, const Eigen::Vector3d& d) const override;

 private:
  SphericalHarmonics sh_;
};

}  // namespace baker
