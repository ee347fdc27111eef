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
  tbb::parallel_for(std::size_t(0), bricks.size(),
                    [&](std::size_t n) { forEachHeldProbeOfBrick(g, level.rows, bricks[n], f); });
}

}  // namespace

bool onLevelBorder(const ProbeGrid& g, const ProbeRows& placed, int i, int j, int k) {
  for (int dz = -1; dz <= 1; ++dz)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const int a = i + dx, b = j + dy, c = k + dz;
        if (a < 0 || b < 0 || c < 0 || a >= g.dims.x() || b >= g.dims.y() || c >= g.dims.z()) continue;
        if (placed.row(g, a, b, c) < 0) return true;
      }
  return false;
}

void markLevelBorder(Volume& level, const ProbeRows& placed) {
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
                     level.visibility.data() + row * level.visibilityPerProbe,
                     level.keepsSkyDirect ? level.skyDirect.data() + row * level.coefficientsPerProbe : nullptr,
                     level.keepsSkyBounced ? level.skyBounced.data() + row * level.coefficientsPerProbe : nullptr);
      });
    fillInvalidProbes(level.grid, level.rows, level.states, level.coefficientsPerProbe, level.coefficients);
    fillInvalidProbes(level.grid, level.rows, level.states, level.visibilityPerProbe, level.visibility);
    fillInvalidProbes(level.grid, level.rows, level.states, level.skyDirectPerProbe(), level.skyDirect);
    fillInvalidProbes(level.grid, level.rows, level.states, level.skyBouncedPerProbe(), level.skyBounced);
    // Dropped before finer levels read this one, so that their border probes take what a reader
    // of the file samples.
    const std::vector<bool> keep = bricksWorthStoring(level);
    level = keepBricks(std::move(level), keep);
  }
}

}  // namespace baker
