#pragma once
#include <Eigen/Core>

#include "validate/LatLongEnvironment.h"

namespace baker {

// The irradiance of the environment at the direction of every texel, by the exact sum over
// all texels: E(n) = Σ_t L_t max(0, n·ω_t) ΔΩ_t (texels × RGB, in texel order). This is the
// reference of the Ambient Dice paper's irradiance table, without its Monte Carlo noise. The
// clamped cosine is sampled at texel centres, so even a constant environment L gets πL only to
// within 3e-5 relative at 256 × 128 (texels the horizon cuts count wholly or not at all).
// O(texels²) work done as dense matrix products in parallel: 0.5 s for 256 × 128 on 2 cores.
Eigen::MatrixX3d exactIrradiance(const LatLongEnvironment& environment);

// The error measure of the paper's table, on E/π (the radiance a white Lambertian surface
// would reflect): per channel the mean squared error over the image's pixels, unweighted,
// averaged over the three channels, then the square root. Both arguments hold E.
double irradianceRmse(const Eigen::MatrixX3d& irradiance, const Eigen::MatrixX3d& reference);

}  // namespace baker
