#pragma once
#include <cstdint>
#include <vector>

#include "volume/AdaptiveVolume.h"

namespace baker {

// Per linear brick index of `grid`: whether `bricks` (a level's placement) holds it.
std::vector<bool> placedBricks(const ProbeGrid& grid, const std::vector<std::int64_t>& bricks);

// Whether probe (i, j, k) of `grid` has one of its 26 neighbours inside the grid in a brick
// `placed` does not hold: a border probe of a finer level.
bool onLevelBorder(const ProbeGrid& grid, const std::vector<bool>& placed, int i, int j, int k);

// Marks ProbeState::Interpolated the border probes of a finer level's held bricks: those with one
// of their 26 neighbours inside the grid in a brick `placed` does not hold. Decided by the
// placement alone, so that a shard holding some of the level's bricks marks the same probes as
// the whole bake. The bake does not trace them; finishAdaptiveLevels gives them their values.
void markLevelBorder(Volume& level, const std::vector<bool>& placed);

// What an adaptive bake does once every level is traced (in one process, or its shards' parts
// put together), level by level, coarsest first, so that a finer level reads the coarser ones as
// a file holds them:
//  - border probes (markLevelBorder) take the coarser levels' interpolated value there, so that
//    interpolated irradiance is continuous where the level changes (docs/ADAPTIVE.md);
//  - Invalid probes are filled from their own level's neighbours;
//  - the level keeps only the bricks worth storing (StoredBricks.h).
void finishAdaptiveLevels(AdaptiveVolume& volume);

}  // namespace baker
