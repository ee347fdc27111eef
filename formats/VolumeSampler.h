#pragma once
#include <Eigen/Core>
#include <string>
#include <vector>

#include "basis/Basis.h"
#include "volume/AdaptiveVolume.h"
#include "volume/LeakAwareInterpolation.h"
#include "volume/Volume.h"

namespace baker {

// What an engine does with a volume at a world position (volume/ProbeInterpolation.h).
struct VolumeSample {
  Eigen::Vector3d gridPosition;  // continuous probe index after clamping
  std::vector<float> coefficients;
  std::vector<float> visibility;
};

VolumeSample sampleVolume(const Volume& volume, const Eigen::Vector3d& world);

// A volume read at a point on a surface as an engine reads it (`baker sample`): the finest level
// holding the eight probes around the point, interpolated trilinearly or, with `leakAware`,
// weighed against leaks (volume/LeakAwareInterpolation.h) and renormalised.
struct SurfaceReading : VolumeSample {
  int level = 0;
  ProbeInterpolation interpolation;
  LeakAwareCorner corners[8];  // the weights leak-aware reading gave, when it was asked for
};
// InputError naming `source` when leak-aware reading is asked of a level without distance maps.
SurfaceReading sampleOnSurface(const AdaptiveVolume& levels, const Eigen::Vector3d& point, const Eigen::Vector3d& normal,
                              bool leakAware, const std::string& source);

// Sky visibility V(n) from visibility coefficients in the basis's channel-0 functions.
double reconstructVisibility(const Basis& basis, const float* visibility, const Eigen::Vector3d& normal);

}  // namespace baker
