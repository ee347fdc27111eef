#pragma once
#include <cstdint>
#include <vector>

#include "volume/AdaptiveVolume.h"

namespace baker {

// Whether probe (i, j, k) of `grid` has one of its 26 neighbours inside the grid that `placed` (a
// level's placement) does not hold: a border probe of a finer level.
bool onLevelBorder(const ProbeGrid& grid, const ProbeRows& placed, int i, int j, int k);

// Marks ProbeState::Interpolated the border probes of a finer level's held probes: those with one
// of their 26 neighbours inside the grid that `placed` does not hold. Decided by the placement
// alone, so that a shard holding some of the level's bricks marks the same probes as the whole
// bake. The bake does not trace them; finishAdaptiveLevels gives them their values.
void markLevelBorder(Volume& level, const ProbeRows& placed);

// What an adaptive bake does once every level is traced (in one process, or its shards' parts
// put together), level by level, coarsest first, so that a finer level reads the coarser ones as
// a file holds them:
//  - border probes (markLevelBorder) take the coarser levels' interpolated value there, so that
//    interpolated irradiance is continuous where the level changes (docs/ADAPTIVE.md);
//  - Invalid probes are filled from their own level's neighbours;
//  - the level keeps only the bricks worth storing (StoredBricks.h).
void finishAdaptiveLevels(AdaptiveVolume& volume);

}  // namespace baker
