#include "bake/AdaptiveBaker.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <chrono>

#include "common/Error.h"
#include "volume/InvalidProbeFill.h"
#include "volume/MemoryEstimate.h"
#include "volume/StoredBricks.h"

namespace baker {
namespace {

// Whether a neighbour of probe (i, j, k) inside the grid is not held.
bool onBorder(const Volume& level, int i, int j, int k) {
  const ProbeGrid& g = level.grid;
  for (int dz = -1; dz <= 1; ++dz)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const int a = i + dx, b = j + dy, c = k + dz;
        if (a < 0 || b < 0 || c < 0 || a >= g.dims.x() || b >= g.dims.y() || c >= g.dims.z()) continue;
        if (level.rows.row(g, a, b, c) < 0) return true;
      }
  return false;
}

// Gives the border probes of `levels[index]` the interpolated value of the levels before it.
void interpolateBorder(std::vector<Volume>& levels, int index) {
  Volume& level = levels[std::size_t(index)];
  const ProbeGrid& g = level.grid;
  const std::vector<std::int64_t>& bricks = level.rows.bricks();
  tbb::parallel_for(std::size_t(0), bricks.size(), [&](std::size_t n) {
    const Eigen::Vector3i lo = g.brickCorner(bricks[n]), hi = lo + g.brickExtent(bricks[n]);
    for (int k = lo.z(); k < hi.z(); ++k)
      for (int j = lo.y(); j < hi.y(); ++j)
        for (int i = lo.x(); i < hi.x(); ++i) {
          if (!onBorder(level, i, j, k)) continue;
          const std::int64_t row = level.rows.row(g, i, j, k);
          level.states[std::size_t(row)] = ProbeState::Interpolated;
          sampleLevels(levels, index, g.position(i, j, k), level.coefficients.data() + row * level.coefficientsPerProbe,
                       level.visibility.data() + row * level.visibilityPerProbe);
        }
  });
}

}  // namespace

AdaptiveVolume bakeAdaptive(const Scene& scene, const RayTracer& tracer, const Basis& basis,
                            const AdaptivePlacement& placement, const BakeSettings& settings, BakeStats* stats,
                            const std::function<void(std::int64_t, std::int64_t)>& progress) {
  const double needed = volumeMemoryBytes(double(placement.probes()), basis);
  if (needed > double(physicalMemoryBytes()))
    throw SettingError("spacing", fmt::format(": {} probes over {} levels in {} need about {:.3g} GiB, more than this "
                                              "machine has; nothing was traced (raise the spacing or lower the levels)",
                                              placement.probes(), placement.levels(), basis.name(), needed / double(1ull << 30)));
  const BrickBaker baker(scene, tracer, basis, settings);
  const auto start = std::chrono::steady_clock::now();
  if (stats) *stats = BakeStats{};
  std::int64_t brickCount = 0;
  for (const std::vector<std::int64_t>& bricks : placement.bricks) brickCount += std::int64_t(bricks.size());
  std::atomic<std::int64_t> bricksDone{0};

  AdaptiveVolume volume;
  volume.marginCells = placement.marginCells;
  // The finest level draws the streams of a uniform bake of its grid; each coarser level those
  // after every finer level's.
  std::vector<std::uint64_t> firstIds(std::size_t(placement.levels()), 0);
  for (int index = placement.levels() - 2; index >= 0; index -= 1)
    firstIds[std::size_t(index)] = firstIds[std::size_t(index) + 1] + std::uint64_t(placement.grids[std::size_t(index) + 1].probeCount());
  for (int index = 0; index < placement.levels(); ++index) {
    const ProbeGrid& grid = placement.grids[std::size_t(index)];
    const std::vector<std::int64_t>& bricks = placement.bricks[std::size_t(index)];
    const bool everyBrick = std::int64_t(bricks.size()) == grid.brickCount();
    volume.levels.push_back(baker.emptyVolume(grid, everyBrick ? ProbeRows() : ProbeRows(grid, bricks)));
    if (index > 0) interpolateBorder(volume.levels, index);
    Volume& level = volume.levels.back();
    baker.bake(level, bricks, firstIds[std::size_t(index)], stats, [&] {
      const std::int64_t done = ++bricksDone;
      if (progress) progress(done, brickCount);
    });
    fillInvalidProbes(grid, level.rows, level.states, level.coefficientsPerProbe, level.coefficients);
    fillInvalidProbes(grid, level.rows, level.states, level.visibilityPerProbe, level.visibility);
    requireFiniteBake(level);
    // Dropped before finer levels read this one, so that their border probes take what a reader
    // of the file samples.
    const std::vector<bool> keep = bricksWorthStoring(level);
    level = keepBricks(std::move(level), keep);
  }
  std::vector<const Volume*> levels;
  for (const Volume& level : volume.levels) levels.push_back(&level);
  baker.finishStats(levels, stats);
  if (stats) stats->traceSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return volume;
}

}  // namespace baker
