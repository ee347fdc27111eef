#pragma once
#include <Eigen/Core>
#include <vector>

#include "basis/Basis.h"
#include "volume/Volume.h"

namespace baker {

// What an engine does with a volume at a world position (volume/ProbeInterpolation.h).
struct VolumeSample {
  Eigen::Vector3d gridPosition;  // continuous probe index after clamping
  std::vector<float> coefficients;
  std::vector<float> visibility;
};

VolumeSample sampleVolume(const Volume& volume, const Eigen::Vector3d& world);

// Sky visibility V(n) from visibility coefficients in the basis's channel-0 functions.
double reconstructVisibility(const Basis& basis, const float* visibility, const Eigen::Vector3d& normal);

}  // namespace baker
