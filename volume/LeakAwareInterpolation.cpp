#include "volume/LeakAwareInterpolation.h"

#include <stdexcept>

namespace baker {

bool weighAgainstLeaks(const Volume& v, const Eigen::Vector3d& point, const Eigen::Vector3d& normal,
                       ProbeInterpolation& interpolation, LeakAwareCorner* corners) {
  const int perProbe = v.distanceMomentsPerProbe();
  if (perProbe == 0) throw std::logic_error("weighAgainstLeaks: the volume holds no distance moments");
  const ProbeGrid& g = v.grid;
  bool changed = false;
  for (int n = 0; n < interpolation.corners; ++n) {
    const std::int64_t row = interpolation.held[n];
    if (row < 0) continue;
    const std::int64_t p = v.rows.probeAt(g, row);
    const Eigen::Vector3i probe = g.indexOf(p);
    Eigen::Vector3d baked = g.position(p);
    if (!v.offsets.empty()) baked += v.offsets[std::size_t(row)].cast<double>();
    const double leak = leakWeight(v.distanceMap, v.distanceMoments.data() + row * perProbe, baked, point, normal, g.spacing);
    if (corners) corners[n] = {probe, interpolation.weights[n], leak};
    if (leak == 1.0) continue;
    interpolation.weights[n] *= leak;
    changed = true;
  }
  return changed;
}

}  // namespace baker
