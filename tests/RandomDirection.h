#pragma once
#include <Eigen/Core>
#include <random>

namespace baker::test {

// A direction uniform on the sphere: a normalised Gaussian vector (one shorter than 1e-6, which
// normalising would blow up, is drawn again).
template <typename Engine>
Eigen::Vector3d randomDirection(Engine& rng) {
  std::normal_distribution<double> gaussian;
  Eigen::Vector3d d;
  do d = Eigen::Vector3d(gaussian(rng), gaussian(rng), gaussian(rng));
  while (d.norm() < 1e-6);
  return d.normalized();
}

}  // namespace baker::test
