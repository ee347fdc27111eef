#include "basis/DirectionSet.h"

#include <cmath>
#include <stdexcept>

namespace baker {

DirectionSet sphericalFibonacci(int n) {
  if (n <= 0) throw std::invalid_argument("direction count must be positive");
  DirectionSet set;
  set.directions.reserve(n);
  set.weights.assign(n, 4.0 * M_PI / n);
  const double goldenAngle = M_PI * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < n; ++i) {
    const double z = 1.0 - (2.0 * i + 1.0) / n;
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    const double phi = goldenAngle * i;
    set.directions.emplace_back(r * std::cos(phi), r * std::sin(phi), z);
  }
  return set;
}

}  // namespace baker
