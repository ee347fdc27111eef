#pragma once
#include <Eigen/Core>
#include <functional>
#include <map>
#include <string>

#include "basis/DirectionSet.h"
#include "basis/SphericalFunctions.h"

namespace baker {

// The Gauss order per quadrature piece used for every exact inner product. Doubling it changes
// no Gram or moment entry of any basis by more than 1e-12 relative (SphereQuadratureTest).
constexpr int kExactQuadratureOrder = 16;

// Inner products ∫ f_i g_j dω with the piecewise quadrature split along both sets' kinks, or,
// when both sets are polynomials (SH), exactly by a Gauss product rule whatever `order`.
Eigen::MatrixXd innerProducts(const SphericalFunctions& f, const SphericalFunctions& g,
                              int order = kExactQuadratureOrder);

// Clamped-cosine convolution factors for orthonormal real SH: A0 = π, A1 = 2π/3, A2 = π/4,
// odd l > 1 vanish, even l = 2π(−1)^(l/2−1)/((l+2)(l−1)) · l!/(2^l ((l/2)!)²).
double clampedCosineBand(int l);

// Optional band window for the radiance→irradiance operator (paper eq. 8): none, or a Hann
// window h_l = (1 + cos(πl/(w+1)))/2 that fades bands out up to width w, which trades a little
// sharpness for less ringing.
struct BandWindow {
  int hannWidth = 0;  // 0: no window
  double factor(int l) const;
};

struct ShReproduction {
  // ‖I − P[0:n, 0:n]‖_F with P = B_shᵀ G⁻¹ B_sh and n = (L+1)², for L = 0..maxOrder.
  std::vector<double> cumulative;
  // √(Σ_{k≤L} cumulative(k)²): the definition that reproduces the paper's Ambient Dice rows.
  std::vector<double> runningSum;
};

// Everything derived from one function set's Gram matrix G_ij = ∫ f_i f_j dω, built once in
// double precision and cached per SH order.
class GramOperators {
 public:
  // `functions` must outlive this object (SH moments are computed on demand).
  // Throws NumericalError naming `label` (and an SG set's sharpness) when the functions are too
  // sharp for the exact quadrature to resolve, or G is numerically singular: such a basis is
  // refused, never regularised.
  GramOperators(const SphericalFunctions& functions, std::string label);

  const Eigen::MatrixXd& gram() const { return gram_; }
  const Eigen::MatrixXd& gramInverse() const { return inverse_; }
  double conditionNumber() const { return condition_; }

  // B_sh(i, j) = ∫ f_i Y_j dω for SH up to order L.
  const Eigen::MatrixXd& shMoments(int order) const;
  // Coefficients of the least-squares fit of an SH expansion of order L: G⁻¹ B_sh.
  Eigen::MatrixXd fromSh(int order) const { return inverse_ * shMoments(order); }
  // Coefficients from samples at directions with quadrature weights: G⁻¹ Bᵀ W (moments by the
  // samples' quadrature, Gram exact). Contrast leastSquaresProjection, which fits the samples.
  Eigen::MatrixXd fromSamples(const DirectionSet& samples) const;

  // Radiance coefficients → irradiance coefficients (paper eq. 7), G⁻¹ B_sh C B_shᵀ, summing SH
  // bands until no entry changes by more than 1e-6 of the largest. Reports the order used.
  Eigen::MatrixXd radianceToIrradiance(const BandWindow& window = {}, int* orderUsed = nullptr) const;

  // SH coefficients of radiance up to `order` → irradiance coefficients: G⁻¹ B_sh C. Bands that
  // C (with the window) multiplies by zero are not integrated; their columns are zero.
  Eigen::MatrixXd irradianceFromSh(int order, const BandWindow& window = {}) const;

  ShReproduction shReproduction(int maxOrder) const;

 private:
  // Builds operatorAtOrder(8), (16), … until consecutive results agree to 1e-6 of the largest entry.
  Eigen::MatrixXd convergedBandSum(const std::function<Eigen::MatrixXd(int)>& operatorAtOrder, int* orderUsed) const;
  // diag(C) with the window applied: A_l·h_l for every (l, m) up to `order`.
  static Eigen::VectorXd bandFactors(int order, const BandWindow& window);

  const SphericalFunctions& functions_;
  std::string label_;
  Eigen::MatrixXd gram_, inverse_;
  double condition_ = 0.0;
  mutable std::map<int, Eigen::MatrixXd> shMoments_;
};

// The highest SH order a set of n well-spread directions resolves with margin: the largest L
// with 4·(L+1)² ≤ n (the fit then stays near-orthogonal: condition number close to 1).
int resolvableShOrder(std::size_t sampleCount);

// The inverse of a symmetric positive definite matrix through its eigendecomposition, with
// its condition number; throws NumericalError naming `label` above 1e12 or when not positive.
Eigen::MatrixXd invertSymmetric(const Eigen::MatrixXd& matrix, const std::string& label, double* conditionNumber);

}  // namespace baker
