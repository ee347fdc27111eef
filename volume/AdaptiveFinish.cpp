#include "volume/AdaptiveFinish.h"

#include <tbb/parallel_for.h>

#include "volume/InvalidProbeFill.h"
#include "volume/StoredBricks.h"

namespace baker {
namespace {

// Every held probe of `level`, in parallel over its bricks: f(i, j, k, row).
template <typename F>
void forEachHeldProbe(const Volume& level, const F& f) {
  const ProbeGrid& g = level.grid;
  const std::vector<std::int64_t> bricks = heldBricksInOrder(level);
  tbb::parallel_for(std::size_t(0), bricks.size(), [&](std::size_t n) {
    const Eigen::Vector3i lo = g.brickCorner(bricks[n]), hi = lo + g.brickExtent(bricks[n]);
    for (int k = lo.z(); k < hi.z(); ++k)
      for (int j = lo.y(); j < hi.y(); ++j)
        for (int i = lo.x(); i < hi.x(); ++i) f(i, j, k, level.rows.row(g, i, j, k));
  });
}

}  // namespace

bool onLevelBorder(const ProbeGrid& g, const std::vector<bool>& placed, int i, int j, int k) {
  for (int dz = -1; dz <= 1; ++dz)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const int a = i + dx, b = j + dy, c = k + dz;
        if (a < 0 || b < 0 || c < 0 || a >= g.dims.x() || b >= g.dims.y() || c >= g.dims.z()) continue;
        if (!placed[std::size_t(g.brickOf(a, b, c))]) return true;
      }
  return false;
}

std::vector<bool> placedBricks(const ProbeGrid& grid, const std::vector<std::int64_t>& bricks) {
  std::vector<bool> placed(std::size_t(grid.brickCount()), false);
  for (const std::int64_t b : bricks) placed[std::size_t(b)] = true;
  return placed;
}

void markLevelBorder(Volume& level, const std::vector<bool>& placed) {
  forEachHeldProbe(level, [&](int i, int j, int k, std::int64_t row) {
    if (onLevelBorder(level.grid, placed, i, j, k)) level.states[std::size_t(row)] = ProbeState::Interpolated;
  });
}

void finishAdaptiveLevels(AdaptiveVolume& volume) {
  for (int index = 0; index < int(volume.levels.size()); ++index) {
    Volume& level = volume.levels[std::size_t(index)];
    if (index > 0)
      forEachHeldProbe(level, [&](int i, int j, int k, std::int64_t row) {
        if (level.states[std::size_t(row)] != ProbeState::Interpolated) return;
        sampleLevels(volume.levels, index, level.grid.position(i, j, k),
                     level.coefficients.data() + row * level.coefficientsPerProbe,
                     level.visibility.data() + row * level.visibilityPerProbe);
      });
    fillInvalidProbes(level.grid, level.rows, level.states, level.coefficientsPerProbe, level.coefficients);
    fillInvalidProbes(level.grid, level.rows, level.states, level.visibilityPerProbe, level.visibility);
    // Dropped before finer levels read this one, so that their border probes take what a reader
    // of the file samples.
    const std::vector<bool> keep = bricksWorthStoring(level);
    level = keepBricks(std::move(level), keep);
  }
}

}  // namespace baker
