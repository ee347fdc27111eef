#include "bake/GramOperators.h"

#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <functional>

#include "bake/ProjectionOperator.h"
#include "bake/SphereQuadrature.h"
#include "bake/SphericalGaussianBasis.h"
#include "bake/SphericalHarmonics.h"
#include "common/Error.h"

namespace baker {
namespace {

constexpr double kMaxConditionNumber = 1e12;
// Every exact integral is promised to 1e-9. Each function's squared norm, the sharpest
// integrand of the Gram matrix, is integrated again at this finer order to hold to that.
constexpr int kCheckQuadratureOrder = 24;
constexpr double kMaxQuadratureDisagreement = 1e-9;
// Refused, not regularised: an engine reconstructs with the basis's own functions, so
// coefficients from a damped inverse would stand for a different function than they claim.
constexpr const char* kRefusal = "baker refuses such a basis rather than regularising it";

// The samples of every function of `f` at the quadrature's directions, one row per direction.
Eigen::MatrixXd sampleFunctions(const SphericalFunctions& f, const DirectionSet& q) {
  Eigen::MatrixXd values(q.size(), f.count());
  Eigen::VectorXd row(f.count());
  for (std::size_t k = 0; k < q.size(); ++k) {
    f.evaluate(q.directions[k], row.data());
    values.row(k) = row.transpose();
  }
  return values;
}

Eigen::VectorXd weightsOf(const DirectionSet& q) { return Eigen::Map<const Eigen::VectorXd>(q.weights.data(), q.size()); }

// ∫ f_i² dω for every function, with the piecewise quadrature of `order`.
Eigen::VectorXd squaredNorms(const SphericalFunctions& f, int order) {
  const DirectionSet q = piecewiseSphereQuadrature(order, f.kinkPlanes());
  return sampleFunctions(f, q).cwiseAbs2().transpose() * weightsOf(q);
}

// Lobes far sharper than a quadrature piece fall between its nodes: the Gram matrix comes out
// wrong, and often still well conditioned, so only a second, finer rule can tell.
void requireResolvedByQuadrature(const SphericalFunctions& f, const Eigen::MatrixXd& gram, const std::string& label) {
  const Eigen::VectorXd finer = squaredNorms(f, kCheckQuadratureOrder);
  const double disagreement = (gram.diagonal() - finer).cwiseAbs().maxCoeff() / finer.cwiseAbs().maxCoeff();
  if (!(disagreement <= kMaxQuadratureDisagreement))
    throw NumericalError(fmt::format("{}: the functions are too sharp to integrate exactly (their norms change by "
                                     "{:.2g} between quadrature orders {} and {}, more than {:.0e}); {}",
                                     label, disagreement, kExactQuadratureOrder, kCheckQuadratureOrder,
                                     kMaxQuadratureDisagreement, kRefusal));
}

// Names the function set in messages; for spherical Gaussians with the sharpness that decides
// whether they can be integrated and told apart.
std::string describe(const SphericalFunctions& f, const std::string& label) {
  if (const auto* lobes = dynamic_cast<const SphericalGaussians*>(&f))
    return fmt::format("{} with --sg-sharpness {}", label, lobes->sharpness());
  return label;
}

}  // namespace

Eigen::MatrixXd innerProducts(const SphericalFunctions& f, const SphericalFunctions& g, int order) {
  std::vector<Eigen::Vector3d> kinks = f.kinkPlanes();
  for (const Eigen::Vector3d& n : g.kinkPlanes()) kinks.push_back(n);
  const DirectionSet q = piecewiseSphereQuadrature(order, kinks);
  const Eigen::MatrixXd fv = sampleFunctions(f, q);
  if (&f == &g) return fv.transpose() * weightsOf(q).asDiagonal() * fv;
  return fv.transpose() * weightsOf(q).asDiagonal() * sampleFunctions(g, q);
}

double clampedCosineBand(int l) {
  if (l == 0) return M_PI;
  if (l == 1) return 2.0 * M_PI / 3.0;
  if (l % 2 == 1) return 0.0;
  // l!/(2^l ((l/2)!)²) built as a product to stay in range.
  double ratio = 1.0;
  for (int k = 1; k <= l / 2; ++k) ratio *= double(l / 2 + k) / (4.0 * k);
  const double sign = (l / 2 - 1) % 2 == 0 ? 1.0 : -1.0;
  return 2.0 * M_PI * sign / ((l + 2.0) * (l - 1.0)) * ratio;
}

double BandWindow::factor(int l) const {
  if (hannWidth <= 0) return 1.0;
  if (l > hannWidth) return 0.0;
  return 0.5 * (1.0 + std::cos(M_PI * l / (hannWidth + 1.0)));
}

Eigen::MatrixXd invertSymmetric(const Eigen::MatrixXd& matrix, const std::string& label, double* conditionNumber) {
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(matrix);
  const double smallest = eigen.eigenvalues().minCoeff(), largest = eigen.eigenvalues().maxCoeff();
  const double condition = smallest > 0.0 ? largest / smallest : std::numeric_limits<double>::infinity();
  if (conditionNumber) *conditionNumber = condition;
  if (!(condition <= kMaxConditionNumber))
    throw NumericalError(fmt::format("{}: the Gram matrix is numerically singular (condition number {:.3g} > {:.0e}): "
                                     "the functions are too broad or too alike to tell apart; {}",
                                     label, condition, kMaxConditionNumber, kRefusal));
  return eigen.eigenvectors() * eigen.eigenvalues().cwiseInverse().asDiagonal() * eigen.eigenvectors().transpose();
}

GramOperators::GramOperators(const SphericalFunctions& functions, std::string label)
    : functions_(functions), label_(describe(functions, label)) {
  gram_ = innerProducts(functions, functions);
  gram_ = 0.5 * (gram_ + gram_.transpose());  // exact symmetry, not rounding-level
  requireResolvedByQuadrature(functions, gram_, label_);
  inverse_ = invertSymmetric(gram_, label_, &condition_);
}

const Eigen::MatrixXd& GramOperators::shMoments(int order) const {
  auto it = shMoments_.find(order);
  if (it != shMoments_.end()) return it->second;
  const SphericalHarmonics sh(order);
  return shMoments_[order] = innerProducts(functions_, sh);
}

Eigen::MatrixXd GramOperators::fromSamples(const DirectionSet& samples) const {
  return inverse_ * sampleFunctions(functions_, samples).transpose() * weightsOf(samples).asDiagonal();
}

Eigen::MatrixXd GramOperators::convergedBandSum(const std::function<Eigen::MatrixXd(int)>& operatorAtOrder,
                                                int* orderUsed) const {
  Eigen::MatrixXd previous;
  for (int order = 8;; order += 8) {
    Eigen::MatrixXd op = operatorAtOrder(order);
    if (previous.size() && (op - previous).cwiseAbs().maxCoeff() <= 1e-6 * op.cwiseAbs().maxCoeff()) {
      if (orderUsed) *orderUsed = order;
      return op;
    }
    if (order + 8 > SphericalHarmonics::kMaxOrder)
      throw NumericalError(fmt::format("{}: the irradiance operator has not converged at SH order {}", label_, order));
    previous = std::move(op);
  }
}

Eigen::VectorXd GramOperators::bandFactors(int order, const BandWindow& window) {
  Eigen::VectorXd c((order + 1) * (order + 1));
  for (int l = 0; l <= order; ++l)
    for (int m = -l; m <= l; ++m) c[l * l + l + m] = clampedCosineBand(l) * window.factor(l);
  return c;
}

Eigen::MatrixXd GramOperators::radianceToIrradiance(const BandWindow& window, int* orderUsed) const {
  return convergedBandSum(
      [&](int order) {
        const Eigen::MatrixXd& b = shMoments(order);
        return Eigen::MatrixXd(inverse_ * b * bandFactors(order, window).asDiagonal() * b.transpose());
      },
      orderUsed);
}

int resolvableShOrder(std::size_t sampleCount) {
  int order = 0;
  while (order + 1 <= SphericalHarmonics::kMaxOrder && std::size_t((order + 2) * (order + 2)) * 4 <= sampleCount)
    ++order;
  return order;
}

Eigen::MatrixXd GramOperators::irradianceFromSamples(const DirectionSet& samples, int shOrder,
                                                     const BandWindow& window) const {
  const SphericalHarmonics sh(shOrder);
  const ProjectionOperator fit = leastSquaresProjection(sh, samples, label_ + " (SH fit of the samples)");
  return irradianceFromSh(shOrder, window) * fit.matrix;
}

Eigen::MatrixXd GramOperators::irradianceFromSh(int order, const BandWindow& window) const {
  return inverse_ * shMoments(order) * bandFactors(order, window).asDiagonal();
}

ShReproduction GramOperators::shReproduction(int maxOrder) const {
  const Eigen::MatrixXd& b = shMoments(maxOrder);
  const Eigen::MatrixXd p = b.transpose() * inverse_ * b;
  ShReproduction r;
  double sum = 0.0;
  for (int l = 0; l <= maxOrder; ++l) {
    const int n = (l + 1) * (l + 1);
    const double norm = (Eigen::MatrixXd::Identity(n, n) - p.topLeftCorner(n, n)).norm();
    sum += norm * norm;
    r.cumulative.push_back(norm);
    r.runningSum.push_back(std::sqrt(sum));
  }
  return r;
}

}  // namespace baker
