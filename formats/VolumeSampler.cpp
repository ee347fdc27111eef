#include "formats/VolumeSampler.h"

#include <algorithm>
#include <cmath>

namespace baker {

VolumeSample sampleVolume(const Volume& v, const Eigen::Vector3d& world) {
  const ProbeGrid& g = v.grid;
  VolumeSample s;
  s.gridPosition = (world - g.origin) / g.spacing;
  int lo[3];
  double t[3];
  for (int a = 0; a < 3; ++a) {
    s.gridPosition[a] = std::clamp(s.gridPosition[a], 0.0, double(g.dims[a] - 1));
    lo[a] = std::min(int(std::floor(s.gridPosition[a])), std::max(0, g.dims[a] - 2));
    t[a] = g.dims[a] > 1 ? s.gridPosition[a] - lo[a] : 0.0;
  }
  s.coefficients.assign(v.coefficientsPerProbe, 0.0f);
  s.visibility.assign(v.visibilityPerProbe, 0.0f);
  for (int corner = 0; corner < 8; ++corner) {
    int index[3];
    double weight = 1.0;
    for (int a = 0; a < 3; ++a) {
      const int step = (corner >> a) & 1;
      if (step && g.dims[a] == 1) weight = 0.0;
      index[a] = std::min(lo[a] + step, g.dims[a] - 1);
      weight *= step ? t[a] : 1.0 - t[a];
    }
    if (weight == 0.0) continue;
    const std::int64_t p = g.linearIndex(index[0], index[1], index[2]);
    for (int c = 0; c < v.coefficientsPerProbe; ++c)
      s.coefficients[c] += float(weight * v.coefficients[p * v.coefficientsPerProbe + c]);
    for (int c = 0; c < v.visibilityPerProbe; ++c)
      s.visibility[c] += float(weight * v.visibility[p * v.visibilityPerProbe + c]);
  }
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
