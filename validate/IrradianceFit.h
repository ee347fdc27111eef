#pragma once
#include <Eigen/Core>
#include <string>
#include <vector>

#include "basis/Basis.h"
#include "validate/LatLongEnvironment.h"

namespace baker {

// One way of representing an environment's irradiance in a basis, evaluated at every texel.
struct IrradianceFit {
  std::string method;               // stable key: "unclamped", "clamped", "weighted_fit", "unweighted_fit"
  std::string description;          // one line for people
  std::vector<float> coefficients;  // one probe's coefficients of E, in Basis's layout
  Eigen::MatrixX3d irradiance;      // E from Basis::reconstruct at every texel direction
  double rmse = 0.0;                // irradianceRmse(irradiance, reference)
  // Least squares fits: the largest condition number of the sampled Gram matrices BᵀWB (how
  // much the coefficients amplify noise). 0 for SH, which needs no solve.
  double conditionNumber = 0.0;
};

// The Ambient Dice paper's methodology (section 4), against `reference` = exactIrradiance:
// - SH bases: the radiance projected by the texel sum, convolved with the clamped cosine
//   (Funk–Hecke factors A_l), reconstructed as it is ("unclamped", the paper's rows) and
//   clamped at 0 ("clamped");
// - every other basis: least squares fits to the exact irradiance at the texel directions,
//   with solid-angle weights ("weighted_fit") and with all texels weighted equally
//   ("unweighted_fit", the reading that matches the paper's cos²cos⁴ row).
// The first fit is the primary one. NumericalError when a fit is numerically singular.
std::vector<IrradianceFit> fitIrradiance(const Basis& basis, const LatLongEnvironment& environment,
                                         const Eigen::MatrixX3d& reference);

}  // namespace baker
