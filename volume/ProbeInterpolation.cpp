#include "volume/ProbeInterpolation.h"

#include <algorithm>
#include <cmath>

namespace baker {

ProbeInterpolation interpolationAt(const Volume& v, const Eigen::Vector3d& world) {
  const ProbeGrid& g = v.grid;
  ProbeInterpolation s;
  s.gridPosition = (world - g.origin) / g.spacing;
  int lo[3];
  double t[3];
  for (int a = 0; a < 3; ++a) {
    s.gridPosition[a] = std::clamp(s.gridPosition[a], 0.0, double(g.dims[a] - 1));
    lo[a] = std::min(int(std::floor(s.gridPosition[a])), std::max(0, g.dims[a] - 2));
    t[a] = g.dims[a] > 1 ? s.gridPosition[a] - lo[a] : 0.0;
  }
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
    s.held[s.corners] = v.rows.row(g, index[0], index[1], index[2]);
    s.weights[s.corners++] = weight;
  }
  return s;
}

bool ProbeInterpolation::complete() const {
  return std::all_of(held, held + corners, [](std::int64_t row) { return row >= 0; });
}

void ProbeInterpolation::apply(const Volume& v, bool renormalise, float* coefficients, float* visibility,
                               float* skyDirect, float* skyBounced) const {
  const auto blend = [&](const std::vector<float>& values, int width, float* out) {
    std::fill_n(out, width, 0.0f);
    double total = 0.0;
    for (int n = 0; n < corners; ++n) {
      if (held[n] < 0) continue;
      total += weights[n];
      for (int c = 0; c < width; ++c) out[c] += float(weights[n] * values[held[n] * width + c]);
    }
    if (!renormalise || total == 0.0 || total == 1.0) return;
    for (int c = 0; c < width; ++c) out[c] = float(out[c] / total);
  };
  blend(v.coefficients, v.coefficientsPerProbe, coefficients);
  blend(v.visibility, v.visibilityPerProbe, visibility);
  if (skyDirect) blend(v.skyDirect, v.skyDirectPerProbe(), skyDirect);
  if (skyBounced) blend(v.skyBounced, v.skyBouncedPerProbe(), skyBounced);
}

}  // namespace baker
