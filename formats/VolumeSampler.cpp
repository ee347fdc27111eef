#include "formats/VolumeSampler.h"

#include <fmt/format.h>

#include "common/Error.h"
#include "volume/ProbeInterpolation.h"

namespace baker {

VolumeSample sampleVolume(const Volume& v, const Eigen::Vector3d& world) {
  const ProbeInterpolation interpolation = interpolationAt(v, world);
  VolumeSample s;
  s.gridPosition = interpolation.gridPosition;
  s.coefficients.resize(std::size_t(v.coefficientsPerProbe));
  s.visibility.resize(std::size_t(v.visibilityPerProbe));
  interpolation.apply(v, /*renormalise=*/false, s.coefficients.data(), s.visibility.data());
  return s;
}

SurfaceReading sampleOnSurface(const AdaptiveVolume& levels, const Eigen::Vector3d& point, const Eigen::Vector3d& normal,
                              bool leakAware, const std::string& source) {
  const LevelChoice choice = finestLevelAt(levels.levels, int(levels.levels.size()), point);
  const Volume& volume = levels.levels[std::size_t(choice.level)];
  if (leakAware && volume.distanceMomentsPerProbe() == 0)
    throw InputError(fmt::format("{}: holds no distance moments, which leak-aware reading needs (bake it again with "
                                 "uniform placement and a distance map)",
                                 source));
  SurfaceReading s;
  s.level = choice.level;
  s.interpolation = choice.interpolation;
  const bool reweighed = leakAware && weighAgainstLeaks(volume, point, normal, s.interpolation, s.corners);
  s.gridPosition = s.interpolation.gridPosition;
  s.coefficients.resize(std::size_t(volume.coefficientsPerProbe));
  s.visibility.resize(std::size_t(volume.visibilityPerProbe));
  s.interpolation.apply(volume, reweighed || !s.interpolation.complete(), s.coefficients.data(), s.visibility.data());
  return s;
}

double reconstructVisibility(const Basis& basis, const float* visibility, const Eigen::Vector3d& normal) {
  const SphericalFunctions& f = basis.functions(0);
  std::vector<double> values(f.count());
  f.evaluate(normal, values.data());
  double sum = 0.0;
  for (int i = 0; i < f.count(); ++i) sum += values[i] * visibility[i];
  return sum;
}

}  // namespace baker
