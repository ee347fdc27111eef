#include "bake/SphericalHarmonics.h"

#include <cmath>
#include <stdexcept>

namespace baker {

SphericalHarmonics::SphericalHarmonics(int order) : order_(order) {
  if (order < 0 || order > kMaxOrder) throw std::invalid_argument("spherical harmonics order out of range");
  normalisation_.resize((order + 1) * (order + 2) / 2);
  for (int l = 0; l <= order; ++l)
    for (int m = 0; m <= l; ++m) {
      // K(l,m) = sqrt((2l+1)/(4π) · (l−m)!/(l+m)!), the ratio of factorials built up stepwise.
      double ratio = 1.0;
      for (int k = l - m + 1; k <= l + m; ++k) ratio /= k;
      double k = std::sqrt((2 * l + 1) / (4.0 * M_PI) * ratio);
      normalisation_[l * (l + 1) / 2 + m] = m == 0 ? k : std::sqrt(2.0) * k;
    }
}

void SphericalHarmonics::evaluate(const Eigen::Vector3d& d, double* values) const {
  const double x = d.x(), y = d.y(), z = d.z();
  // cos(mφ)·sin^m θ and sin(mφ)·sin^m θ are the real and imaginary parts of (x + iy)^m, and
  // P(l,m)(z) / sin^m θ is a polynomial in z: together they avoid angles and divisions.
  double cosPart = 1.0, sinPart = 0.0;  // (x + iy)^m
  double diagonal = 1.0;                // P(m,m)/sin^m θ = (2m−1)!!
  for (int m = 0; m <= order_; ++m) {
    if (m > 0) {
      const double c = cosPart * x - sinPart * y;
      sinPart = cosPart * y + sinPart * x;
      cosPart = c;
      diagonal *= 2 * m - 1;
    }
    double previous = 0.0, current = diagonal;  // P(l−1,m), P(l,m) over sin^m θ, from l = m
    for (int l = m; l <= order_; ++l) {
      if (l > m) {
        const double next = ((2 * l - 1) * z * current - (l + m - 1) * previous) / (l - m);
        previous = current;
        current = next;
      }
      const double scaled = normalisation_[l * (l + 1) / 2 + m] * current;
      const int centre = l * l + l;
      if (m == 0) {
        values[centre] = scaled;
      } else {
        values[centre + m] = scaled * cosPart;
        values[centre - m] = scaled * sinPart;
      }
    }
  }
}

}  // namespace baker
