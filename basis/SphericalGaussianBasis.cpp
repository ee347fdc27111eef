#include "basis/SphericalGaussianBasis.h"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <stdexcept>

#include "basis/BasisRegistry.h"
#include "basis/DirectionSet.h"

namespace baker {
namespace {

std::vector<Eigen::Vector3d> fibonacciAxes(int lobes) {
  if (lobes < 1 || lobes > SphericalGaussianBasis::kMaxLobes)
    throw std::invalid_argument("spherical Gaussian lobe count out of range");
  return sphericalFibonacci(lobes).directions;
}

// The default sharpness, measured with `baker env` (irradiance RMSE of the solid-angle-weighted
// least squares fit to the exact irradiance, ennis and grace) over λ = 0.05 · 1.1^k, k = 0..70
// (k = 0, 2, .., 70 for N = 20, 48, 64), from the checkout:
//   for n in 6 8 9 12 16 24 32; do for k in $(seq 0 70); do
//     l=$(awk "BEGIN{printf \"%.4g\", 0.05*1.1^$k}"); for p in ennis grace; do
//       build/baker env ../shared/data/probes/$p.hdr --basis sg-$n --sg-sharpness $l --json |
//       jq -r '[.basis, .sg_sharpness, .rmse.weighted_fit, .gram_condition_number.weighted_fit] | @tsv'
//     done; done; done
// For N ≤ 12 and 48 the mean RMSE keeps falling as λ → 0 (for 20 it is flat below 0.9): wide
// lobes approach the low-order polynomials smooth irradiance is made of, while their Gram
// matrix degenerates until the fit is refused (condition number 1e12). So λ is the largest value whose mean RMSE is within
// 1 % of the lowest among the λ whose Gram condition number is at most 1e6 (float coefficients
// then keep four significant digits). Measured (mean RMSE of E/π; ennis, grace; condition):
//    N    λ      mean     ennis    grace    cond  | unconstrained argmin λ
//    6  0.278  0.2542   0.4707   0.03768  2.2e4  | → 0 (0.2513 at 0.05, cond 2e7)
//    8  0.448  0.1979   0.3771   0.01865  1.0e4  | → 0 (0.1959 at 0.05, cond 6e7)
//    9  0.209  0.05529  0.09744  0.01314  3.0e5  | → 0 (0.05416 at 0.05, cond 9e7)
//   12  0.542  0.05714  0.1006   0.01365  3.5e5  | → 0 (0.05411 at 0.05, cond 5e11)
//   16  2.26   0.04716  0.08040  0.01392  9.9e2  | 2.06 (0.04670)
//   20  1.28   0.03840  0.06689  0.00990  1.6e5  | 0.72 (0.03821, cond 1e7)
//   24  3.65   0.02912  0.05037  0.00786  5.8e2  | 3.31 (0.02893)
//   32  2.49   0.01748  0.02966  0.00530  9.8e4  | 1.87 (0.01739, cond 1e6)
//   48  3.31   0.00920  0.01514  0.00326  6.1e5  | → 0 (0.00908 at 1.06, cond 2e11)
//   64  5.87   0.00657  0.01007  0.00307  4.5e4  | 4.85 (0.00653, cond 3e5)
// The best λ does not grow smoothly with N (how the Fibonacci points sit relative to the
// polynomial spaces matters), hence a table rather than a formula.
struct MeasuredSharpness {
  int lobes;
  double sharpness;
};
constexpr MeasuredSharpness kTable[] = {{6, 0.278},  {8, 0.448},  {9, 0.209},  {12, 0.542}, {16, 2.26},
                                        {20, 1.28},  {24, 3.65},  {32, 2.49},  {48, 3.31},  {64, 5.87}};

}  // namespace

SphericalGaussians::SphericalGaussians(std::vector<Eigen::Vector3d> axes, double sharpness)
    : axes_(std::move(axes)), sharpness_(sharpness) {
  if (!(sharpness > 0.0) || !std::isfinite(sharpness))
    throw std::invalid_argument("spherical Gaussian sharpness must be positive and finite");
}

void SphericalGaussians::evaluate(const Eigen::Vector3d& d, double* values) const {
  for (std::size_t i = 0; i < axes_.size(); ++i) values[i] = std::exp(sharpness_ * (axes_[i].dot(d) - 1.0));
}

double sphericalGaussianInnerProduct(const Eigen::Vector3d& axis1, double sharpness1, const Eigen::Vector3d& axis2,
                                     double sharpness2) {
  // 4π e^(−s) sinh(r)/r = 2π e^(r−s) (1 − e^(−2r))/r with s = λ1 + λ2 ≥ r: no overflow for
  // sharp lobes, and expm1 keeps (1 − e^(−2r))/r accurate as r → 0 (opposite, equal lobes).
  const double r = (sharpness1 * axis1 + sharpness2 * axis2).norm();
  const double s = sharpness1 + sharpness2;
  const double shape = r > 0.0 ? -std::expm1(-2.0 * r) / r : 2.0;
  return 2.0 * M_PI * std::exp(r - s) * shape;
}

SphericalGaussianBasis::SphericalGaussianBasis(int lobes) : SphericalGaussianBasis(lobes, defaultSharpness(lobes)) {}

SphericalGaussianBasis::SphericalGaussianBasis(int lobes, double sharpness) : lobes_(fibonacciAxes(lobes), sharpness) {}

std::vector<int> SphericalGaussianBasis::measuredLobeCounts() {
  std::vector<int> counts;
  for (const MeasuredSharpness& m : kTable) counts.push_back(m.lobes);
  return counts;
}

double SphericalGaussianBasis::defaultSharpness(int lobes) {
  // Below the table, keep λ/N: N lobes share the sphere, so each covers ~4π/N and λ ∝ N keeps
  // the overlap. In between, interpolate log λ linearly in log N (λ ∝ N^p locally).
  if (lobes <= kTable[0].lobes) return kTable[0].sharpness * lobes / kTable[0].lobes;
  for (std::size_t k = 1; k < std::size(kTable); ++k)
    if (lobes <= kTable[k].lobes) {
      const MeasuredSharpness& a = kTable[k - 1];
      const MeasuredSharpness& b = kTable[k];
      const double t = std::log(double(lobes) / a.lobes) / std::log(double(b.lobes) / a.lobes);
      return a.sharpness * std::pow(b.sharpness / a.sharpness, t);
    }
  throw std::invalid_argument("spherical Gaussian lobe count out of range");
}

Eigen::Vector3f SphericalGaussianBasis::reconstruct(const float* coefficients, const Eigen::Vector3d& d) const {
  // Evaluate the lobes once for all three channels (the generic path evaluates per channel).
  std::array<double, kMaxLobes> values;
  lobes_.evaluate(d, values.data());
  const int n = lobes_.count();
  Eigen::Vector3f color;
  for (int c = 0; c < 3; ++c) {
    double sum = 0.0;
    for (int i = 0; i < n; ++i) sum += values[i] * coefficients[c * n + i];
    color[c] = float(sum);
  }
  return color;
}

int sphericalGaussianLobeCount(const std::string& name) {
  const std::string prefix = "sg-";
  if (name.size() <= prefix.size() || name.size() > prefix.size() + 2 || name.compare(0, prefix.size(), prefix) != 0)
    return 0;
  int lobes = 0;
  for (std::size_t k = prefix.size(); k < name.size(); ++k) {
    if (name[k] < '0' || name[k] > '9') return 0;
    lobes = 10 * lobes + (name[k] - '0');
  }
  if (name[prefix.size()] == '0' || lobes > SphericalGaussianBasis::kMaxLobes) return 0;
  return lobes;
}

namespace {

// sg-N takes any N in 1..64; the list names the counts whose default sharpness was measured.
std::vector<std::string> measuredNames() {
  std::vector<std::string> names;
  for (int n : SphericalGaussianBasis::measuredLobeCounts()) names.push_back("sg-" + std::to_string(n));
  return names;
}

const BasisRegistration kGaussians({70, measuredNames(), {"sg_sharpness"},
                                    [](const std::string& name, const BasisParameters& p) -> std::unique_ptr<Basis> {
                                      const int lobes = sphericalGaussianLobeCount(name);
                                      if (lobes == 0) return nullptr;
                                      if (p.sharpness) return std::make_unique<SphericalGaussianBasis>(lobes, *p.sharpness);
                                      return std::make_unique<SphericalGaussianBasis>(lobes);
                                    }});

}  // namespace

nlohmann::json SphericalGaussians::describe() const {
  nlohmann::json axes = nlohmann::json::array();
  // Adding 0 turns −0 into 0, which some readers print oddly.
  for (const Eigen::Vector3d& a : axes_) axes.push_back({a.x() + 0.0, a.y() + 0.0, a.z() + 0.0});
  return {{"type", "spherical-gaussians"},
          {"sharpness", sharpness()},
          {"lobe", "f_i(n) = exp(sharpness (axes[i].n - 1))"},
          {"axes_rule", "spherical Fibonacci: z = 1 - (2i+1)/count, phi = i pi (3 - sqrt 5), r = sqrt(1 - z^2)"},
          {"axes", axes}};
}

std::string SphericalGaussians::parameterText() const { return fmt::format("sharpness {}", sharpness()); }

std::optional<RadialLobes> SphericalGaussians::radialLobes() const {
  const double lambda = sharpness_;
  return RadialLobes{[lambda](double t) { return std::exp(lambda * (t - 1.0)); }, axes_};
}

BasisParameters SphericalGaussianBasis::parameters() const {
  return {sharpness(), std::nullopt};
}

}  // namespace baker
