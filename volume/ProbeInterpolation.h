#pragma once
#include <Eigen/Core>

#include "volume/Volume.h"

namespace baker {

// What an engine does with a volume at a world position: the probes' coefficients (and sky
// visibility) interpolated trilinearly between the eight probes around it, the position clamped
// to the grid's probes (a 3D texture with clamp-to-edge addressing, sampled at texel centres).
struct ProbeInterpolation {
  Eigen::Vector3d gridPosition;  // continuous probe index after clamping
  int corners = 0;               // probes with a non-zero weight
  std::int64_t held[8];          // their rows in the volume, -1 for a probe it does not hold
  double weights[8];

  // Every probe with a weight is held: the volume covers the position.
  bool complete() const;
  // Writes the weighted sum of the held probes' values; with `renormalise`, divided by the sum of
  // their weights (zeros when none is held). `skyDirect` and `skyBounced`, when given, of a
  // volume that keeps them.
  void apply(const Volume& volume, bool renormalise, float* coefficients, float* visibility,
             float* skyDirect = nullptr, float* skyBounced = nullptr) const;
};

ProbeInterpolation interpolationAt(const Volume& volume, const Eigen::Vector3d& world);

}  // namespace baker
