#include "volume/SkyRadiance.h"

#include <algorithm>
#include <cmath>

namespace baker {

Eigen::Vector2i skyTexelOf(const Eigen::Vector3d& d, int width, int height) {
  const double u = 0.5 + std::atan2(d.z(), d.x()) / (2.0 * M_PI);
  const double v = std::acos(std::clamp(d.y(), -1.0, 1.0)) / M_PI;
  return {std::clamp(int(std::floor(u * width)), 0, width - 1), std::clamp(int(std::floor(v * height)), 0, height - 1)};
}

double latLongSolidAngle(double du, double v0, double v1) {
  return 2.0 * M_PI * du * (std::cos(M_PI * v0) - std::cos(M_PI * v1));
}

}  // namespace baker
