#pragma once
#include <functional>
#include <string>
#include <vector>

namespace baker {

// The diffuse response of a radial lobe g(a·ω), K(n) = ∫ g(a·ω) max(0, n·ω) dω = h(a·n), as the
// Legendre series h(x) = Σ_l k_l P_l(x). By the Funk–Hecke theorem k_l = (2l+1)/(4π)·A_l·λ_l,
// with λ_l = 2π ∫ g(t) P_l(t) dt the lobe's and A_l the clamped cosine's band factors. A_l = 0 for
// odd l > 1, so a lobe that is a clamped even polynomial has a finite series (max(0, t)² gives
// π(1 + x)²/8 exactly); other lobes are cut where the rest of the series adds at most 1e-7 of
// h(1), the response's largest value.
class LegendreResponse {
 public:
  static constexpr int kMaxTerms = 256;
  // NumericalError naming `label` when the series has not converged within kMaxTerms − 32
  // terms (a lobe too sharp: a spherical Gaussian with λ above about 3000).
  LegendreResponse(const std::function<double(double)>& profile, const std::string& label);

  // k_0 … k_L: the terms that are kept.
  const std::vector<double>& coefficients() const { return coefficients_; }
  double operator()(double x) const { return legendreSeries(coefficients_, x); }

  // Σ_l k[l] P_l(x) by the three-term recurrence.
  static double legendreSeries(const std::vector<double>& k, double x);

 private:
  std::vector<double> coefficients_;
};

}  // namespace baker
