#include "bake/ProjectionOperator.h"

#include <fmt/format.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <limits>

#include "common/Error.h"

namespace baker {
namespace {

// Past this the solve loses more than ~4 of double's 16 digits plus float storage noise:
// the set of directions no longer pins the coefficients down.
constexpr double kMaxConditionNumber = 1e12;

// The sampled Gram matrix BᵀWB, factored once its condition number has passed, and BᵀW.
struct WeightedFit {
  Eigen::MatrixXd weightedBasis;  // f × n, column k: w_k · B(k, :)
  Eigen::LDLT<Eigen::MatrixXd> gram;
  double conditionNumber = 0.0;
};

WeightedFit weightedFit(const SphericalFunctions& functions, const DirectionSet& samples, const std::string& label) {
  const int n = int(samples.size());
  const int f = functions.count();
  WeightedFit fit;
  fit.weightedBasis.resize(f, n);
  Eigen::MatrixXd basis(n, f);
  Eigen::VectorXd values(f);
  for (int k = 0; k < n; ++k) {
    functions.evaluate(samples.directions[k], values.data());
    basis.row(k) = values.transpose();
    fit.weightedBasis.col(k) = samples.weights[k] * values;
  }
  const Eigen::MatrixXd gram = fit.weightedBasis * basis;
  // The condition number needs only the spectrum, which is cheaper without the eigenvectors.
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(gram, Eigen::EigenvaluesOnly);
  const double smallest = eigen.eigenvalues().minCoeff();
  const double largest = eigen.eigenvalues().maxCoeff();
  fit.conditionNumber = smallest > 0.0 ? largest / smallest : std::numeric_limits<double>::infinity();
  if (!(fit.conditionNumber <= kMaxConditionNumber))
    throw NumericalError(fmt::format(
        "{}: {} sample directions cannot resolve its {} functions (condition number {:.3g} > {:.0e}); use more rays",
        label, n, f, fit.conditionNumber, kMaxConditionNumber));
  fit.gram.compute(gram);
  return fit;
}

}  // namespace

ProjectionOperator leastSquaresProjection(const SphericalFunctions& functions, const DirectionSet& samples,
                                          const std::string& label) {
  const WeightedFit fit = weightedFit(functions, samples, label);
  ProjectionOperator op;
  op.matrix = fit.gram.solve(fit.weightedBasis);
  op.conditionNumber = fit.conditionNumber;
  return op;
}

Eigen::MatrixXd leastSquaresProjection(const Eigen::MatrixXd& left, const SphericalFunctions& functions,
                                       const DirectionSet& samples, const std::string& label) {
  const WeightedFit fit = weightedFit(functions, samples, label);
  // left·(BᵀWB)⁻¹·BᵀW = ((BᵀWB)⁻¹·leftᵀ)ᵀ·BᵀW: the solve takes left's few rows, not every sample.
  return fit.gram.solve(left.transpose()).transpose() * fit.weightedBasis;
}

}  // namespace baker
