#pragma once
#include <Eigen/Core>

#include "basis/SphericalFunctions.h"

namespace baker {

// Minimises ½cᵀGc − mᵀc subject to c ≥ 0 (Lawson–Hanson active set on the normal equations):
// the least-squares projection with moments m restricted to non-negative coefficients. For
// bases of non-negative functions (Ambient Dice linear and SRBF, ambient cube, SG) this also
// makes every reconstruction non-negative, which bounds ringing from very bright small sources.
// Unlike the linear projection it is a per-probe solve. G must be symmetric positive definite.
Eigen::VectorXd nonNegativeProjection(const Eigen::MatrixXd& gram, const Eigen::VectorXd& moments);

// True when no function takes a value below zero (checked at 16384 spherical Fibonacci
// directions, to 1e-9): only then do coefficients >= 0 make every reconstruction >= 0, and only
// then is the non-negative projection worth its per-probe solve.
bool functionsAreNonNegative(const SphericalFunctions& functions);

}  // namespace baker
