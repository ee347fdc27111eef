#pragma once
#include <Eigen/Core>
#include <algorithm>
#include <vector>

namespace baker {

// How the pictures baker draws show irradiance: display-referred, c = x / (1 + x) per channel
// with x = exposure × E (negative E shows black), so that nothing clips and a scene of any
// brightness reads at a glance; written with writeSrgbPng at exposure 1.
inline Eigen::Vector3f displayedColour(const Eigen::Vector3f& e, double exposure) {
  Eigen::Vector3f c;
  for (int i = 0; i < 3; ++i) {
    const double x = std::max(0.0, exposure * e[i]);
    c[i] = float(x / (1.0 + x));
  }
  return c;
}

// The pictures' automatic exposure shows the median at a third of white: 1 / (2 × median).
inline double medianOf(std::vector<double> values) {
  if (values.empty()) return 0.0;
  const auto middle = values.begin() + values.size() / 2;
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

}  // namespace baker
