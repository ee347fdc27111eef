#pragma once
#include <vector>

#include "basis/Basis.h"

namespace baker {

// Unit-amplitude spherical Gaussians G_i(d) = exp(λ(μ_i·d − 1)) sharing one sharpness λ.
// Smooth everywhere, so they need no kink planes.
class SphericalGaussians : public SphericalFunctions {
 public:
  SphericalGaussians(std::vector<Eigen::Vector3d> axes, double sharpness);
  int count() const override { return int(axes_.size()); }
  void evaluate(const Eigen::Vector3d& direction, double* values) const override;
  nlohmann::json describe() const override;
  std::string parameterText() const override;
  std::optional<RadialLobes> radialLobes() const override;
  const std::vector<Eigen::Vector3d>& axes() const { return axes_; }
  double sharpness() const { return sharpness_; }

 private:
  std::vector<Eigen::Vector3d> axes_;
  double sharpness_;
};

// ∫ G1 G2 dω for unit-amplitude lobes in closed form (Wang et al.; thesis eq. 2.11):
// 4π e^(−(λ1+λ2)) sinh(r)/r with r = ‖λ1μ1 + λ2μ2‖.
double sphericalGaussianInnerProduct(const Eigen::Vector3d& axis1, double sharpness1, const Eigen::Vector3d& axis2,
                                     double sharpness2);

// N spherical Gaussians on the N-point spherical Fibonacci directions for each RGB channel.
// Every lobe is non-zero everywhere, so a lookup reads all 3N coefficients. CLI name "sg-N".
class SphericalGaussianBasis : public Basis {
 public:
  static constexpr int kMaxLobes = 64;
  // The default sharpness for that many lobes (see defaultSharpness).
  explicit SphericalGaussianBasis(int lobes);
  SphericalGaussianBasis(int lobes, double sharpness);

  // The λ that minimises the irradiance RMSE of the fit, measured on two light probes for
  // some N and interpolated in between; see the table in the .cpp.
  static double defaultSharpness(int lobes);
  // The lobe counts whose default sharpness was measured (the ones `baker bases` lists).
  static std::vector<int> measuredLobeCounts();

  std::string name() const override { return "sg-" + std::to_string(lobes_.count()); }
  std::string family() const override { return "spherical-gaussians"; }
  BasisParameters parameters() const override;
  const SphericalFunctions& functions(int) const override { return lobes_; }
  int coefficientsPerLookup() const override { return 3 * lobes_.count(); }
  Eigen::Vector3f reconstruct(const float* coefficients, const Eigen::Vector3d& d) const override;
  double sharpness() const { return lobes_.sharpness(); }

 private:
  SphericalGaussians lobes_;
};

// N when `name` is "sg-N" with 1 ≤ N ≤ kMaxLobes written without leading zeros, else 0.
int sphericalGaussianLobeCount(const std::string& name);

}  // namespace baker
