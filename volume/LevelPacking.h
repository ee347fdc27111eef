#pragma once
#include <cstdint>
#include <vector>

#include "volume/AdaptiveVolume.h"
#include "volume/Shard.h"

namespace baker {

// What an MPI rank sends of its part of an adaptive bake: every level's held bricks, level after
// level, each as packBricks (VolumeAssembly.h) packs bricks in increasing order.
std::vector<float> packLevels(const AdaptiveVolume& part);

// The size of packLevels' result for a part holding `share` (per level, its bricks in increasing
// order and their sub-bricks) of `like`'s levels.
std::size_t packedLevelsSize(const AdaptiveVolume& like, const std::vector<ProbeRows>& share);

// `like` without its values: its levels' grids, basis, settings and shard, its margin and placement.
AdaptiveVolume levelsWithoutValues(const AdaptiveVolume& like);

// Shard `shard`'s part of the bake `like` is a part of, from packLevels' values for its share
// `share`: `like`'s grids and settings, each level holding its share's probes. InputError naming
// the shard when the size or a probe state is wrong.
AdaptiveVolume unpackLevels(const AdaptiveVolume& like, const Shard& shard, const std::vector<ProbeRows>& share,
                            const std::vector<float>& packed);

}  // namespace baker
