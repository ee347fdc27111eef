#include "basis/SphericalHarmonics.h"

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
  recurrence_.resize(normalisation_.size());
  for (int l = 1; l <= order; ++l)
    for (int m = 0; m < l; ++m)
      recurrence_[l * (l + 1) / 2 + m] = {double(2 * l - 1) / (l - m), double(l + m - 1) / (l - m)};
}

void SphericalHarmonics::evaluate(const Eigen::Vector3d& d, double* values) const {
  const double x = d.x(), y = d.y(), z = d.z();
  // cos(mφ)·sin^m θ and sin(mφ)·sin^m θ are the real and imaginary parts of (x + iy)^m, and
  // P(l,m)(z) / sin^m θ is a polynomial in z: together they avoid angles and divisions.
  double cosPart[kMaxOrder + 1], sinPart[kMaxOrder + 1];  // (x + iy)^m
  double previous[kMaxOrder + 1], current[kMaxOrder + 1];  // P(l−1,m), P(l,m) over sin^m θ
  cosPart[0] = 1.0;
  sinPart[0] = 0.0;
  current[0] = 1.0;  // P(m,m)/sin^m θ = (2m−1)!!
  for (int m = 1; m <= order_; ++m) {
    cosPart[m] = cosPart[m - 1] * x - sinPart[m - 1] * y;
    sinPart[m] = cosPart[m - 1] * y + sinPart[m - 1] * x;
    current[m] = current[m - 1] * (2 * m - 1);
  }
  // Band by band, so that the recurrences of the different m run side by side rather than one
  // after another; their factors are worked out once (a division here cost a quarter of the
  // evaluation, which a bake does for every direct-view sample).
  for (int l = 0; l <= order_; ++l) {
    const Recurrence* factors = recurrence_.data() + l * (l + 1) / 2;
    for (int m = 0; m < l; ++m) {
      const double next = factors[m].ofCurrent * z * current[m] - factors[m].ofPrevious * previous[m];
      previous[m] = current[m];
      current[m] = next;
    }
    previous[l] = 0.0;
    const double* norm = normalisation_.data() + l * (l + 1) / 2;
    double* band = values + l * l + l;
    band[0] = norm[0] * current[0];
    for (int m = 1; m <= l; ++m) {
      const double scaled = norm[m] * current[m];
      band[m] = scaled * cosPart[m];
      band[-m] = scaled * sinPart[m];
    }
  }
}

nlohmann::json SphericalHarmonics::describe() const {
  return {{"type", "sh"},
          {"order", order_},
          {"convention",
           "real, orthonormal (integral of Y_i Y_j over the sphere = delta_ij), polar axis z, no Condon-Shortley "
           "phase; index l*l+l+m; m>0 ~ cos(m phi), m<0 ~ sin(|m| phi), phi = atan2(y, x); "
           "Y(1,-1) = c y, Y(1,0) = c z, Y(1,1) = c x with c = sqrt(3/(4 pi))"}};
}

}  // namespace baker
