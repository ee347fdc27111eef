#pragma once
#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <string>

#include "basis/DirectionSet.h"
#include "basis/SphericalFunctions.h"

namespace baker {

// Maps radiance samples at a direction set to basis coefficients: c = P · L, with P of size
// count() × directions. Built in double precision once per function set and direction set.
struct ProjectionOperator {
  Eigen::MatrixXd matrix;
  double conditionNumber = 0.0;  // of the sampled Gram matrix BᵀWB
};

// Weighted least squares of `functions` over samples at a direction set: P = (BᵀWB)⁻¹BᵀW,
// B(k,i) = f_i(ω_k), W = diag(w), with BᵀWB factored once, so that every operator applied after
// the same fit shares one factorisation. It reproduces every function in the span exactly,
// whatever the direction set, as long as the set resolves the functions.
class SampledFit {
 public:
  // Check: throws NumericalError, naming `label`, when BᵀWB is numerically singular (too few or
  // badly spread directions for the functions). CheckedByRotation: the set is a rotation of one
  // whose fit passed, and the functions span a rotation-invariant space (SH up to an order):
  // rotating the set turns BᵀWB into D·BᵀWB·Dᵀ with D orthogonal, so its spectrum, and with it
  // the condition number, is the one already checked.
  enum class Conditioning { Check, CheckedByRotation };

  SampledFit(const SphericalFunctions& functions, const DirectionSet& samples, const std::string& label,
             Conditioning conditioning = Conditioning::Check);

  // Of BᵀWB; 0 when the conditioning was not computed (CheckedByRotation).
  double conditionNumber() const { return conditionNumber_; }
  // P itself.
  Eigen::MatrixXd matrix() const;
  // left · P for an operator `left` applied after the fit: ((BᵀWB)⁻¹·leftᵀ)ᵀ·BᵀW, whose solve
  // takes left's few rows rather than every sample.
  Eigen::MatrixXd after(const Eigen::MatrixXd& left) const;

 private:
  Eigen::MatrixXd weightedBasis_;  // f × n, column k: w_k · B(k, :)
  Eigen::LDLT<Eigen::MatrixXd> gram_;
  double conditionNumber_ = 0.0;
};

// P and its condition number for one function set; throws as SampledFit's Check.
ProjectionOperator leastSquaresProjection(const SphericalFunctions& functions, const DirectionSet& samples,
                                          const std::string& label);

}  // namespace baker
