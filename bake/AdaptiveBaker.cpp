#include "bake/AdaptiveBaker.h"

#include <fmt/format.h>

#include <atomic>
#include <chrono>
#include <optional>

#include "common/Error.h"
#include "volume/AdaptiveFinish.h"
#include "volume/MemoryEstimate.h"
#include "volume/Shard.h"

namespace baker {

AdaptiveVolume bakeAdaptive(const Scene& scene, const RayTracer& tracer, const Basis& basis,
                            const AdaptivePlacement& placement, const BakeSettings& settings, BakeStats* stats,
                            const std::function<void(std::int64_t, std::int64_t)>& progress,
                            const std::optional<Shard>& shard) {
  const std::vector<std::vector<std::int64_t>> share =
      shard ? shardLevelBricks(placement.grids, placement.bricks, *shard) : placement.bricks;
  std::vector<ProbeRows> shareRows;  // moved into the levels as they are made
  std::int64_t brickCount = 0, probes = 0;
  for (int level = 0; level < placement.levels(); ++level) {
    shareRows.push_back(placement.rows(level, share[std::size_t(level)]));
    brickCount += std::int64_t(share[std::size_t(level)].size());
    probes += shareRows.back().count(placement.grids[std::size_t(level)]);
  }
  const double needed = volumeMemoryBytes(double(probes), basis);
  if (needed > double(physicalMemoryBytes()))
    throw SettingError("spacing", fmt::format(": {} probes over {} levels in {} need about {:.3g} GiB, more than this "
                                              "machine has; nothing was traced (raise the spacing, lower the levels or "
                                              "cut the bake into shards)",
                                              probes, placement.levels(), basis.name(), needed / double(1ull << 30)));
  const BrickBaker baker(scene, tracer, basis, settings);
  const auto start = std::chrono::steady_clock::now();
  if (stats) *stats = BakeStats{};
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
    const std::vector<std::int64_t>& bricks = share[std::size_t(index)];
    ProbeRows rows = std::move(shareRows[std::size_t(index)]);
    const bool everyProbe = std::int64_t(bricks.size()) == grid.brickCount() && !rows.holdsPartialBricks();
    volume.levels.push_back(baker.emptyVolume(grid, everyProbe ? ProbeRows() : std::move(rows)));
    Volume& level = volume.levels.back();
    level.shard = shard;
    if (index > 0) markLevelBorder(level, shard ? placement.rows(index) : level.rows);
    baker.bake(level, bricks, firstIds[std::size_t(index)], stats, [&] {
      const std::int64_t done = ++bricksDone;
      if (progress) progress(done, brickCount);
    });
  }
  // The states as traced, before the finish drops bricks not worth storing.
  std::vector<const Volume*> levels;
  for (const Volume& level : volume.levels) levels.push_back(&level);
  baker.finishStats(levels, stats);
  if (shard) {
    volume.placement = summarizePlacement(placement.bricks, placement.masks);
  } else {
    finishAdaptiveLevels(volume);
  }
  // A part's too: a rank sends its values unchecked, and the merge's fill would spread a NaN.
  for (const Volume& level : volume.levels) requireFiniteBake(level);
  if (stats) stats->traceSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return volume;
}

}  // namespace baker
