#include "formats/VolumeSampler.h"

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

double reconstructVisibility(const Basis& basis, const float* visibility, const Eigen::Vector3d& normal) {
  const SphericalFunctions& f = basis.functions(0);
  std::vector<double> values(f.count());
  f.evaluate(normal, values.data());
  double sum = 0.0;
  for (int i = 0; i < f.count(); ++i) sum += values[i] * visibility[i];
  return sum;
}

}  // namespace baker
