#pragma once
#include <Eigen/Core>
#include <vector>

namespace baker {

// Directions on the unit sphere with quadrature weights: summing to 4π for a rule over the
// sphere, to the integral of its weight function for a weighted rule (GgxLobe::quadrature).
struct DirectionSet {
  std::vector<Eigen::Vector3d> directions;
  std::vector<double> weights;
  std::size_t size() const { return directions.size(); }
};

// The spherical Fibonacci set of n points: equal-area bands in z, golden-angle steps in φ,
// each point weighted 4π/n. Fixed for a given n, so bakes are reproducible.
DirectionSet sphericalFibonacci(int n);

}  // namespace baker
