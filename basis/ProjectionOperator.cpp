#include "basis/ProjectionOperator.h"

#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include <limits>

#include "common/Error.h"

namespace baker {
namespace {

// Past this the solve loses more than ~4 of double's 16 digits plus float storage noise:
// the set of directions no longer pins the coefficients down.
constexpr double kMaxConditionNumber = 1e12;

}  // namespace

SampledFit::SampledFit(const SphericalFunctions& functions, const DirectionSet& samples, const std::string& label,
                       Conditioning conditioning) {
  const int n = int(samples.size());
  const int f = functions.count();
  weightedBasis_.resize(f, n);
  Eigen::MatrixXd basis(n, f);
  Eigen::VectorXd values(f);
  for (int k = 0; k < n; ++k) {
    functions.evaluate(samples.directions[k], values.data());
    basis.row(k) = values.transpose();
    weightedBasis_.col(k) = samples.weights[k] * values;
  }
  // Only the lower triangle: the eigenvalues and the LDLT read nothing else, and the product
  // costs half as much.
  Eigen::MatrixXd gram = Eigen::MatrixXd::Zero(f, f);
  gram.triangularView<Eigen::Lower>() = weightedBasis_ * basis;
  if (conditioning == Conditioning::Check) {
    // The condition number needs only the spectrum, which is cheaper without the eigenvectors.
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(gram, Eigen::EigenvaluesOnly);
    const double smallest = eigen.eigenvalues().minCoeff();
    const double largest = eigen.eigenvalues().maxCoeff();
    conditionNumber_ = smallest > 0.0 ? largest / smallest : std::numeric_limits<double>::infinity();
    if (!(conditionNumber_ <= kMaxConditionNumber))
      throw NumericalError(fmt::format(
          "{}: {} sample directions cannot resolve its {} functions (condition number {:.3g} > {:.0e}); use more rays",
          label, n, f, conditionNumber_, kMaxConditionNumber));
  }
  gram_.compute(gram);
}

Eigen::MatrixXd SampledFit::matrix() const { return gram_.solve(weightedBasis_); }

Eigen::MatrixXd SampledFit::after(const Eigen::MatrixXd& left) const {
  return gram_.solve(left.transpose()).transpose() * weightedBasis_;
}

ProjectionOperator leastSquaresProjection(const SphericalFunctions& functions, const DirectionSet& samples,
                                          const std::string& label) {
  const SampledFit fit(functions, samples, label);
  return {fit.matrix(), fit.conditionNumber()};
}

}  // namespace baker
