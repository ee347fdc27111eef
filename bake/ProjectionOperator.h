#pragma once
#include <Eigen/Core>
#include <string>

#include "bake/DirectionSet.h"
#include "bake/SphericalFunctions.h"

namespace baker {

// Maps radiance samples at a direction set to basis coefficients: c = P · L, with P of size
// count() × directions. Built in double precision once per function set and direction set.
struct ProjectionOperator {
  Eigen::MatrixXd matrix;
  double conditionNumber = 0.0;  // of the sampled Gram matrix BᵀWB
};

// Weighted least squares over the samples: P = (BᵀWB)⁻¹BᵀW, B(k,i) = f_i(ω_k), W = diag(w).
// It reproduces every function in the span exactly, whatever the direction set, as long as
// the set resolves the functions. Throws NumericalError when BᵀWB is numerically singular
// (too few or badly spread directions for the basis); `label` names the basis in the message.
ProjectionOperator leastSquaresProjection(const SphericalFunctions& functions, const DirectionSet& samples,
                                          const std::string& label);

// left · P for a `left` of few rows (an operator applied after the fit), checked the same way;
// cheaper than forming P when left has fewer rows than there are samples.
Eigen::MatrixXd leastSquaresProjection(const Eigen::MatrixXd& left, const SphericalFunctions& functions,
                                       const DirectionSet& samples, const std::string& label);

}  // namespace baker
