#include "formats/LevelChecks.h"

#include <fmt/format.h>

#include "common/Error.h"
#include "formats/VolumeHeader.h"
#include "volume/LevelGrids.h"
#include "volume/MemoryEstimate.h"

namespace baker {

void LevelChecks::grid(int level, const ProbeGrid& grid, const std::string& key) {
  if (level > 0 && !nestsIn(grid, parent_))
    throw InputError(fmt::format("{}: {}origin and spacing do not nest in level {} (each level has a third of the "
                                 "spacing of the one above, its probes on the same lattice)",
                                 path_, key, level - 1));
  const Eigen::Vector3i& d = grid.dims;
  if (d.minCoeff() <= 0 || d.maxCoeff() > kMaxProbesPerAxis || double(grid.brickCount()) > kMaxLevelBricks)
    throw InputError(fmt::format("{}: level {}'s dims ({}, {}, {}) are not a valid grid size", path_, level, d.x(), d.y(), d.z()));
  parent_ = grid;
}

void LevelChecks::margin(int cells, const std::string& key) const {
  if (cells < kMinMarginCells || cells > kMaxMarginCells)
    throw InputError(fmt::format("{}: {} is {}; a placement's margin is {} to {} cells", path_, key, cells,
                                 kMinMarginCells, kMaxMarginCells));
}

void LevelChecks::held(int level, std::size_t bricks) {
  held_ += double(bricks) * kBrickSize * kBrickSize * kBrickSize;
  if (held_ > kMaxProbesRead || volumeMemoryBytes(held_, basis_) / 2 > double(physicalMemoryBytes()))
    throw InputError(fmt::format("{}: levels 0 to {} hold up to {:.3g} probes, more than a volume may hold or this "
                                 "machine's memory",
                                 path_, level, held_));
}

}  // namespace baker
