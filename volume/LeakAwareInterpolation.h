#pragma once
#include <Eigen/Core>

#include "volume/ProbeInterpolation.h"
#include "volume/Volume.h"

namespace baker {

// Each corner's trilinear weight and the factor leakWeight (volume/DistanceMoments.h) gave it.
struct LeakAwareCorner {
  Eigen::Vector3i probe;
  double trilinear = 0.0, leak = 1.0;
};

// Turns a trilinear interpolation at `point` (on a surface of unit `normal`) leak-aware: each
// held corner's weight times its leakWeight, seen from where the probe was baked (its grid
// position plus its offset). Returns whether any weight changed, in which case the caller
// renormalises (ProbeInterpolation::apply); in open space none does, and the interpolation is
// the trilinear one bit for bit. Requires volume.distanceMomentsPerProbe() > 0.
bool weighAgainstLeaks(const Volume& volume, const Eigen::Vector3d& point, const Eigen::Vector3d& normal,
                       ProbeInterpolation& interpolation, LeakAwareCorner* corners = nullptr);

}  // namespace baker
