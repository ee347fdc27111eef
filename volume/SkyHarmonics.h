#pragma once
#include <Eigen/Core>

#include "volume/SkyRadiance.h"

namespace baker {

// A sky as decoders relight at run time: its radiance's real SH to band 2, L_lm = ∫ L(ω) Y_lm(ω) dω
// (the SH of the sh-l2 basis: orthonormal, index l² + l + m, Y_1,−1 ∝ y, Y_1,0 ∝ z, Y_1,1 ∝ x, in
// world axes), per RGB channel. An engine computes the same nine numbers from its own sky.
struct SkyHarmonics {
  Eigen::Matrix<double, 9, 3> radiance = Eigen::Matrix<double, 9, 3>::Zero();

  // Integrated over each texel's patch (its mean radiance, 2 × 2 Gauss points in φ and cos θ).
  static SkyHarmonics of(const SkyRadiance& sky);
  // The sky's irradiance on an unoccluded surface of unit normal n, E(n) = Σ A_l L_lm Y_lm(n)
  // (A_0 = π, A_1 = 2π/3, A_2 = π/4): exact for the sky's band ≤ 2 part, which is all but 1–3 %
  // of any sky's irradiance (the clamped cosine's bands beyond 2 are small).
  Eigen::Vector3d irradiance(const Eigen::Vector3d& normal) const;
};

}  // namespace baker
