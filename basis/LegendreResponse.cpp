#include "basis/LegendreResponse.h"

#include <fmt/format.h>

#include <cmath>

#include "basis/GramOperators.h"
#include "basis/Quadrature.h"
#include "common/Error.h"

namespace baker {
namespace {

// Gauss–Legendre nodes on each of [−1, 0] and [0, 1]: clamped lobes kink at t = 0, and each half
// is then a polynomial of degree below 2·kNodes for every term kept; spherical Gaussians are
// smooth, and sharp ones need the many nodes near t = 1.
constexpr int kNodes = 320;

// λ_l = 2π ∫ g(t) P_l(t) dt for l < kMaxTerms.
std::vector<double> lobeBands(const std::function<double(double)>& profile) {
  std::vector<double> nodes, weights;
  gaussLegendre(kNodes, &nodes, &weights);
  std::vector<double> bands(LegendreResponse::kMaxTerms, 0.0);
  for (double half : {-1.0, 1.0}) {
    for (int q = 0; q < kNodes; ++q) {
      const double t = 0.5 * (nodes[q] + half), w = 0.5 * weights[q] * profile(t);
      double previous = 1.0, current = t;
      bands[0] += w;
      bands[1] += w * t;
      for (int l = 2; l < LegendreResponse::kMaxTerms; ++l) {
        const double next = ((2.0 * l - 1.0) * t * current - (l - 1.0) * previous) / l;
        previous = current;
        current = next;
        bands[l] += w * current;
      }
    }
  }
  for (double& band : bands) band *= 2.0 * M_PI;
  return bands;
}

}  // namespace

LegendreResponse::LegendreResponse(const std::function<double(double)>& profile, const std::string& label) {
  const std::vector<double> bands = lobeBands(profile);
  std::vector<double> k(kMaxTerms);
  for (int l = 0; l < kMaxTerms; ++l) k[l] = (2.0 * l + 1.0) / (4.0 * M_PI) * clampedCosineBand(l) * bands[l];
  const double peak = std::abs(legendreSeries(k, 1.0));
  // Keep terms up to the last whose tail (the terms after it) exceeds the tolerance; terms the
  // quadrature leaves at rounding level (odd l > 1, even l beyond a polynomial's degree) go.
  double tail = 0.0;
  int kept = kMaxTerms;
  while (kept > 1 && tail + std::abs(k[kept - 1]) <= 1e-7 * peak) tail += std::abs(k[--kept]);
  if (kept > kMaxTerms - 32)
    throw NumericalError(fmt::format("{}: the diffuse response of its lobe has not converged in {} Legendre terms",
                                     label, kMaxTerms - 32));
  k.resize(std::size_t(kept));
  coefficients_ = std::move(k);
}

double LegendreResponse::legendreSeries(const std::vector<double>& k, double x) {
  if (k.empty()) return 0.0;
  double sum = k[0], previous = 1.0, current = x;
  for (std::size_t l = 1; l < k.size(); ++l) {
    if (l > 1) {
      const double next = ((2.0 * l - 1.0) * x * current - (l - 1.0) * previous) / double(l);
      previous = current;
      current = next;
    }
    sum += k[l] * current;
  }
  return sum;
}

}  // namespace baker
