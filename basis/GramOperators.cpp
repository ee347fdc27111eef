#include "basis/GramOperators.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

#include "basis/Quadrature.h"
#include "basis/SphereQuadrature.h"
#include "basis/SphericalHarmonics.h"
#include "common/Error.h"

namespace baker {
namespace {

constexpr double kMaxConditionNumber = 1e12;
// Every exact integral is promised to 1e-9. Each function's squared norm, the sharpest
// integrand of the Gram matrix, is integrated again at this finer order to hold to that.
constexpr int kCheckQuadratureOrder = 24;
constexpr double kMaxQuadratureDisagreement = 1e-9;
// Doubling the quadrature order moves no entry by more than this, relative to the largest
// (GramOperators.h): smaller entries are quadrature rounding, not integrals.
constexpr double kQuadratureAccuracy = 1e-12;
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

// An entry that is zero in exact arithmetic (an SH basis's moment with another SH band, say)
// comes out of the quadrature as ±1e-17. Left in an operator, that noise reaches every probe's
// coefficients as values no reader can tell from signal, and costs a volume its compression:
// rounding noise does not compress, exact zeros do.
Eigen::MatrixXd withoutRoundingNoise(Eigen::MatrixXd op) {
  const double floor = kQuadratureAccuracy * op.cwiseAbs().maxCoeff();
  for (Eigen::Index k = 0; k < op.size(); ++k)
    if (std::abs(op.data()[k]) <= floor) op.data()[k] = 0.0;
  return op;
}

Eigen::VectorXd weightsOf(const DirectionSet& q) { return Eigen::Map<const Eigen::VectorXd>(q.weights.data(), q.size()); }

bool isPolynomial(const SphericalFunctions& f) { return f.polynomialDegree() >= 0; }

// A rule for every product f_i·g_j: the Gauss product rule of the two sets' combined degree
// when both are polynomials (exact, a few hundred nodes), otherwise the piecewise rule of
// `order` split along both sets' kinks.
DirectionSet productQuadrature(const SphericalFunctions& f, const SphericalFunctions& g, int order) {
  if (isPolynomial(f) && isPolynomial(g)) {
    const int degree = f.polynomialDegree() + g.polynomialDegree();
    return gaussProductSphere(degree / 2 + 1, degree + 1);
  }
  std::vector<Eigen::Vector3d> kinks = f.kinkPlanes();
  for (const Eigen::Vector3d& n : g.kinkPlanes()) kinks.push_back(n);
  return piecewiseSphereQuadrature(order, kinks);
}

// Σ_k w_k f(d_k) g(d_k)ᵀ over the rule, one block of nodes at a time: a table of every value at
// every node would take count × nodes doubles, nearly 1 GB for SH of order 24 on the tiling.
// Locally supported functions (Ambient Dice: a quarter of the sphere each) are zero on most
// blocks, whose nodes follow the tiling piece by piece: each block's product takes only the
// rows of f that are non-zero on it. Chunks of blocks run in parallel, each summing its blocks in
// order, and the chunks' sums are added in order: chunks are fixed by the rule alone, so any
// number of threads gives the same bits.
Eigen::MatrixXd weightedProducts(const SphericalFunctions& f, const SphericalFunctions& g, const DirectionSet& q) {
  constexpr std::size_t kBlock = 512;
  constexpr std::size_t kChunk = 16 * kBlock;
  const bool same = &f == &g;
  const std::size_t chunks = (q.size() + kChunk - 1) / kChunk;
  std::vector<Eigen::MatrixXd> partial(chunks);
  tbb::parallel_for(std::size_t(0), chunks, [&](std::size_t chunk) {
    Eigen::MatrixXd& sum = partial[chunk];
    sum.setZero(f.count(), g.count());
    Eigen::MatrixXd fValues(f.count(), kBlock), gValues(same ? 0 : g.count(), kBlock);
    Eigen::MatrixXd weighted, active;  // the non-zero rows of f: weighted, and (for f·f) plain
    std::vector<int> rows;
    const std::size_t end = std::min(q.size(), (chunk + 1) * kChunk);
    for (std::size_t first = chunk * kChunk; first < end; first += kBlock) {
      const int n = int(std::min(kBlock, end - first));
      for (int k = 0; k < n; ++k) {
        f.evaluate(q.directions[first + k], fValues.col(k).data());
        if (!same) g.evaluate(q.directions[first + k], gValues.col(k).data());
      }
      rows.clear();
      for (int i = 0; i < f.count(); ++i)
        if (!(fValues.row(i).leftCols(n).array() == 0.0).all()) rows.push_back(i);
      const int r = int(rows.size());
      weighted.resize(r, n);
      active.resize(same ? r : 0, n);
      for (int a = 0; a < r; ++a)
        for (int k = 0; k < n; ++k) {
          weighted(a, k) = q.weights[first + k] * fValues(rows[a], k);
          if (same) active(a, k) = fValues(rows[a], k);
        }
      const Eigen::MatrixXd block = weighted * (same ? active : gValues.leftCols(n)).transpose();
      for (int a = 0; a < r; ++a) {
        if (same)
          for (int b = 0; b < r; ++b) sum(rows[a], rows[b]) += block(a, b);
        else
          sum.row(rows[a]) += block.row(a);
      }
    }
  });
  Eigen::MatrixXd sum = Eigen::MatrixXd::Zero(f.count(), g.count());
  for (const Eigen::MatrixXd& p : partial) sum += p;
  return sum;
}

// The real SH of one order restricted to some of its bands, in index order. An operator that
// weights bands by the clamped cosine multiplies every odd band above 1 by zero: their moments,
// over half of all at high orders, need not be integrated.
class ShBandSubset : public SphericalFunctions {
 public:
  ShBandSubset(int order, const std::vector<int>& bands) : sh_(order) {
    for (int l : bands)
      for (int i = l * l; i < (l + 1) * (l + 1); ++i) indices_.push_back(i);
  }
  const std::vector<int>& indices() const { return indices_; }
  int count() const override { return int(indices_.size()); }
  void evaluate(const Eigen::Vector3d& direction, double* values) const override {
    thread_local std::vector<double> all;
    all.resize(std::size_t(sh_.count()));
    sh_.evaluate(direction, all.data());
    for (std::size_t k = 0; k < indices_.size(); ++k) values[k] = all[std::size_t(indices_[k])];
  }
  int polynomialDegree() const override { return sh_.order(); }

 private:
  SphericalHarmonics sh_;
  std::vector<int> indices_;
};

// ∫ f_i² dω for every function, with the piecewise quadrature of `order`.
Eigen::VectorXd squaredNorms(const SphericalFunctions& f, int order) {
  return sumOverSphereQuadrature(order, f.kinkPlanes(), f.count(), [&](const DirectionSet& nodes, Eigen::VectorXd* sum) {
    Eigen::VectorXd values(f.count());
    for (std::size_t k = 0; k < nodes.size(); ++k) {
      f.evaluate(nodes.directions[k], values.data());
      *sum += nodes.weights[k] * values.cwiseAbs2();
    }
  });
}

// Lobes far sharper than a quadrature piece fall between its nodes: the Gram matrix comes out
// wrong, and often still well conditioned, so only a second, finer rule can tell. Polynomials
// have nothing to fall between the nodes of their exact rule.
void requireResolvedByQuadrature(const SphericalFunctions& f, const Eigen::MatrixXd& gram, const std::string& label) {
  if (isPolynomial(f)) return;
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
  const std::string parameters = f.parameterText();
  return parameters.empty() ? label : label + " with " + parameters;
}

}  // namespace

Eigen::MatrixXd innerProducts(const SphericalFunctions& f, const SphericalFunctions& g, int order) {
  return weightedProducts(f, g, productQuadrature(f, g, order));
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
        return withoutRoundingNoise(inverse_ * b * bandFactors(order, window).asDiagonal() * b.transpose());
      },
      orderUsed);
}

int resolvableShOrder(std::size_t sampleCount) {
  int order = 0;
  while (order + 1 <= SphericalHarmonics::kMaxOrder && std::size_t((order + 2) * (order + 2)) * 4 <= sampleCount)
    ++order;
  return order;
}

Eigen::MatrixXd GramOperators::irradianceFromSh(int order, const BandWindow& window) const {
  const Eigen::VectorXd factors = bandFactors(order, window);
  std::vector<int> bands;
  for (int l = 0; l <= order; ++l)
    if (factors[l * l] != 0.0) bands.push_back(l);
  const ShBandSubset kept(order, bands);
  Eigen::VectorXd keptFactors(kept.count());
  for (int k = 0; k < kept.count(); ++k) keptFactors[k] = factors[kept.indices()[k]];
  const Eigen::MatrixXd convolved = inverse_ * innerProducts(functions_, kept) * keptFactors.asDiagonal();
  // The bands left out are multiplied by zero: their columns stay zero.
  Eigen::MatrixXd result = Eigen::MatrixXd::Zero(functions_.count(), factors.size());
  for (int k = 0; k < kept.count(); ++k) result.col(kept.indices()[k]) = convolved.col(k);
  return withoutRoundingNoise(std::move(result));
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
