#include "bake/ProjectionOperator.h"

#include <fmt/format.h>

#include <Eigen/Eigenvalues>

#include "common/Error.h"

namespace baker {
namespace {

// Past this the solve loses more than ~4 of double's 16 digits plus float storage noise:
// the set of directions no longer pins the coefficients down.
constexpr double kMaxConditionNumber = 1e12;

}  // namespace

ProjectionOperator leastSquaresProjection(const SphericalFunctions& functions, const DirectionSet& samples,
                                          const std::string& label) {
  const int n = int(samples.size());
  const int f = functions.count();
  Eigen::MatrixXd weightedBasis(f, n);  // column k: w_k · B(k, :)
  Eigen::MatrixXd basis(n, f);
  Eigen::VectorXd values(f);
  for (int k = 0; k < n; ++k) {
    functions.evaluate(samples.directions[k], values.data());
    basis.row(k) = values.transpose();
    weightedBasis.col(k) = samples.weights[k] * values;
  }
  Eigen::MatrixXd gram = weightedBasis * basis;
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(gram);
  const double smallest = eigen.eigenvalues().minCoeff();
  const double largest = eigen.eigenvalues().maxCoeff();
  ProjectionOperator op;
  op.conditionNumber = smallest > 0.0 ? largest / smallest : std::numeric_limits<double>::infinity();
  if (!(op.conditionNumber <= kMaxConditionNumber))
    throw NumericalError(fmt::format(
        "{}: {} sample directions cannot resolve its {} functions (condition number {:.3g} > {:.0e}); use more rays",
        label, n, f, op.conditionNumber, kMaxConditionNumber));
  op.matrix = gram.ldlt().solve(weightedBasis);
  return op;
}

}  // namespace baker
