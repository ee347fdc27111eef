#include "volume/SkyHarmonics.h"

#include <algorithm>
#include <cmath>

#include "basis/GramOperators.h"
#include "basis/SphericalHarmonics.h"

namespace baker {

SkyHarmonics SkyHarmonics::of(const SkyRadiance& sky) {
  const SphericalHarmonics sh(2);
  const double node = 0.5 / std::sqrt(3.0);  // Gauss–Legendre, two points: centre ± this × width
  double y[9];
  SkyHarmonics result;
  for (int row = 0; row < sky.height; ++row) {
    const double mu0 = std::cos(M_PI * row / sky.height), mu1 = std::cos(M_PI * (row + 1) / sky.height);
    for (int column = 0; column < sky.width; ++column) {
      const Eigen::Vector3d radiance = sky.texel(column, row);
      if (radiance.isZero()) continue;
      const double phi0 = 2.0 * M_PI * (double(column) / sky.width - 0.5), dphi = 2.0 * M_PI / sky.width;
      // dω = dφ dμ: each of the four points weighs a quarter of the patch's solid angle.
      const double weight = 0.25 * dphi * (mu0 - mu1);
      for (const double a : {0.5 - node, 0.5 + node})
        for (const double b : {0.5 - node, 0.5 + node}) {
          const double phi = phi0 + a * dphi, mu = mu0 + b * (mu1 - mu0), s = std::sqrt(std::max(0.0, 1.0 - mu * mu));
          sh.evaluate(Eigen::Vector3d(s * std::cos(phi), mu, s * std::sin(phi)), y);
          for (int k = 0; k < 9; ++k) result.radiance.row(k) += (weight * y[k]) * radiance.transpose();
        }
    }
  }
  return result;
}

Eigen::Vector3d SkyHarmonics::irradiance(const Eigen::Vector3d& normal) const {
  double y[9];
  SphericalHarmonics(2).evaluate(normal, y);
  Eigen::Vector3d e = Eigen::Vector3d::Zero();
  for (int k = 0; k < 9; ++k) {
    const int band = k == 0 ? 0 : k < 4 ? 1 : 2;
    e += clampedCosineBand(band) * y[k] * radiance.row(k).transpose();
  }
  return e;
}

}  // namespace baker
