#pragma once
#include <vector>

#include "basis/SphericalFunctions.h"

namespace baker {

// Real spherical harmonics of order 0..L, orthonormal over the sphere (∫ Y_i Y_j dω = δ_ij).
// Index l·l + l + m. Convention: the polar axis is the direction's third component and there
// is no Condon–Shortley phase, applied literally to glTF x, y, z, so Y(1,-1) = c·y,
// Y(1,0) = c·z, Y(1,1) = c·x: the convention of the reference tools' panorama_sh.py.
class SphericalHarmonics : public SphericalFunctions {
 public:
  // High orders serve the radiance→irradiance operator, which sums bands until it converges;
  // the factorial ratios in the normalisation stay within double range up to here.
  static constexpr int kMaxOrder = 64;
  explicit SphericalHarmonics(int order);
  int order() const { return order_; }
  int count() const override { return (order_ + 1) * (order_ + 1); }
  void evaluate(const Eigen::Vector3d& direction, double* values) const override;
  nlohmann::json describe() const override;
  int polynomialDegree() const override { return order_; }
  int shBands() const override { return order_; }

 private:
  int order_;
  // P(l,m) = ofCurrent·z·P(l−1,m) − ofPrevious·P(l−2,m): (2l−1)/(l−m) and (l+m−1)/(l−m).
  struct Recurrence {
    double ofCurrent = 0.0, ofPrevious = 0.0;
  };
  std::vector<Recurrence> recurrence_;  // [l·(l+1)/2 + m], m < l
  std::vector<double> normalisation_;  // [l·(l+1)/2 + m]: √2·K(l,m) for m > 0, K(l,0) for m = 0
};

}  // namespace baker
