#include "volume/MemoryEstimate.h"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "common/Error.h"
#include "volume/ProbeState.h"

namespace baker {

double volumeMemoryBytes(double probes, const Basis& basis, int distanceValues) {
  // The coefficients three times: a bake under a sky keeps the sky's part apart, seen directly
  // and off surfaces (Volume::skyDirect, skyBounced).
  const double values = 3.0 * double(basis.totalCoefficients()) + double(basis.functions(0).count()) + distanceValues;
  const double perProbe = values * sizeof(float) + sizeof(ProbeState) + sizeof(Eigen::Vector3f);
  return 2.0 * probes * perProbe;
}

std::uint64_t physicalMemoryBytes() {
  const long pages = sysconf(_SC_PHYS_PAGES), pageSize = sysconf(_SC_PAGE_SIZE);
  // A system that does not say sets no limit here; the allocation itself will tell.
  if (pages <= 0 || pageSize <= 0) return std::numeric_limits<std::uint64_t>::max();
  return std::uint64_t(pages) * std::uint64_t(pageSize);
}

double bakeMemoryBytes(const ProbeGrid& grid, int shardCount, const Basis& basis, int distanceValues) {
  const double probes = double(grid.dims.x()) * double(grid.dims.y()) * double(grid.dims.z());
  if (shardCount <= 1) return volumeMemoryBytes(probes, basis, distanceValues);
  const Eigen::Vector3d counts = grid.brickCounts().cast<double>();
  const double bricks = counts.prod();
  // A shard is a run of whole bricks, at most ⌈B/N⌉ of them, and full bricks can come first.
  const double shardProbes = std::min(probes, std::ceil(bricks / shardCount) * std::pow(double(kBrickSize), 3));
  // The Morton order of every brick (index and key) and the brick-to-row table.
  const double brickTables = 3.0 * sizeof(std::int64_t) * bricks;
  return volumeMemoryBytes(shardProbes, basis, distanceValues) + brickTables;
}

void requireVolumeFitsInMemory(const ProbeGrid& grid, int shardCount, const Basis& basis, std::uint64_t availableBytes,
                               int distanceValues) {
  const double needed = bakeMemoryBytes(grid, shardCount, basis, distanceValues);
  if (needed <= double(availableBytes)) return;
  const std::string held = shardCount <= 1 ? "" : fmt::format(" (one shard of {})", shardCount);
  throw SettingError("spacing",
                    fmt::format(": a grid of {} × {} × {} probes{} in {} needs about {:.0f} bytes ({:.3g} GiB: the "
                               "values, and as much again while they are written), more than this machine's {} bytes "
                               "of memory; nothing was traced (raise the spacing, or cut the bake into more shards)",
                               grid.dims.x(), grid.dims.y(), grid.dims.z(), held, basis.name(), needed,
                               needed / double(1ull << 30), availableBytes));
}

}  // namespace baker
