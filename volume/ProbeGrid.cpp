#include "volume/ProbeGrid.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "common/Error.h"

namespace baker {

double defaultSpacing(const Eigen::AlignedBox3f& bounds) {
  const double longest = bounds.isEmpty() ? 0.0 : double(bounds.sizes().maxCoeff());
  return longest > 0.0 ? std::min(longest / kDefaultProbesAlongLongestSide, kDefaultMaxSpacing) : kDefaultMaxSpacing;
}

Eigen::Vector3d probesPerAxis(const Eigen::AlignedBox3f& bounds, double spacing) {
  if (bounds.isEmpty()) return Eigen::Vector3d::Ones();
  const Eigen::Vector3d lo = bounds.min().cast<double>(), hi = bounds.max().cast<double>();
  const Eigen::Vector3d extent = hi - lo;
  Eigen::Vector3d cells;
  for (int a = 0; a < 3; ++a) {
    // A flat scene (a ground plane, a panel) has no extent across itself: one layer of probes
    // centred on it would lie in its plane and see through it, so it gets a layer on each side.
    const bool flat = !(extent[a] > 1e-6 * extent.maxCoeff());
    // The bounds are floats, so an extent of a whole number of spacings can come out a few float
    // steps longer, at any scale; that must not add a layer of probes.
    const double rounding = 4.0 * std::numeric_limits<float>::epsilon() * std::max(std::abs(lo[a]), std::abs(hi[a]));
    cells[a] = flat ? 2.0 : std::max(1.0, std::ceil((extent[a] - rounding) / spacing - 1e-9));
  }
  return cells;
}

ProbeGrid makeProbeGrid(const Eigen::AlignedBox3f& bounds, double spacing, std::int64_t maxProbes) {
  ProbeGrid grid;
  if (spacing <= 0.0) spacing = defaultSpacing(bounds);
  if (bounds.isEmpty()) {
    grid.spacing = spacing;
    return grid;
  }
  const Eigen::Vector3d lo = bounds.min().cast<double>(), hi = bounds.max().cast<double>();
  const Eigen::Vector3d extent = hi - lo;
  const Eigen::Vector3d cellCounts = probesPerAxis(bounds, spacing);
  const double cells[3] = {cellCounts.x(), cellCounts.y(), cellCounts.z()};
  for (int a = 0; a < 3; ++a) {
    if (const std::int64_t axisLimit = std::min<std::int64_t>(maxProbes, kMaxProbesPerAxis); cells[a] > double(axisLimit))
      throw SettingError("spacing", fmt::format("{} m gives {:.3g} probes along one axis of a {:.3g} m scene; the limit is {}",
                                                spacing, cells[a], extent[a], axisLimit));
  }
  const double total = cells[0] * cells[1] * cells[2];
  if (total > double(maxProbes))
    throw SettingError("spacing", fmt::format("{} m gives {:.0f} × {:.0f} × {:.0f} = {:.3g} probes; the limit is {} "
                                              "(raise the spacing)",
                                              spacing, cells[0], cells[1], cells[2], total, maxProbes));
  grid.spacing = spacing;
  for (int a = 0; a < 3; ++a) {
    grid.dims[a] = int(cells[a]);
    grid.origin[a] = 0.5 * (lo[a] + hi[a]) - 0.5 * spacing * (cells[a] - 1.0);
  }
  return grid;
}

}  // namespace baker
