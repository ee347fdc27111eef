#include "volume/LevelPacking.h"

#include <fmt/format.h>


#include "common/Error.h"
#include "volume/StoredBricks.h"
#include "volume/VolumeAssembly.h"

namespace baker {

std::vector<float> packLevels(const AdaptiveVolume& part) {
  std::vector<float> packed;
  for (const Volume& level : part.levels) {
    const std::vector<float> values = packBricks(level, heldBricksInOrder(level));
    packed.insert(packed.end(), values.begin(), values.end());
  }
  return packed;
}

std::size_t packedLevelsSize(const AdaptiveVolume& like, const std::vector<ProbeRows>& share) {
  std::size_t size = 0;
  for (std::size_t k = 0; k < like.levels.size(); ++k) {
    const Volume& level = like.levels[k];
    size += packedSize(level, share[k], share[k].bricks());
  }
  return size;
}

AdaptiveVolume levelsWithoutValues(const AdaptiveVolume& like) {
  AdaptiveVolume header;
  header.marginCells = like.marginCells;
  header.placement = like.placement;
  for (const Volume& level : like.levels) header.levels.push_back(volumeWithoutValues(level));
  return header;
}

AdaptiveVolume unpackLevels(const AdaptiveVolume& like, const Shard& shard, const std::vector<ProbeRows>& share,
                            const std::vector<float>& packed) {
  if (packed.size() != packedLevelsSize(like, share))
    throw InputError(fmt::format("shard {}: {} values received, {} expected", shardName(shard), packed.size(),
                                 packedLevelsSize(like, share)));
  AdaptiveVolume part = levelsWithoutValues(like);
  const float* in = packed.data();
  for (std::size_t k = 0; k < part.levels.size(); ++k) {
    Volume& level = part.levels[k];
    const ProbeGrid& grid = level.grid;
    level.shard = shard;
    level.rows = share[k];
    holdZeroProbes(level);
    for (const std::int64_t b : share[k].bricks())
      forEachHeldProbeOfBrick(grid, level.rows, b, [&](int i, int j, int l, std::int64_t row) {
        const float* next = unpackProbe(in, level, row, kProbeStateCount);
        if (!next)
          throw InputError(fmt::format("shard {}: probe {} of level {} has state {}", shardName(shard),
                                       grid.linearIndex(i, j, l), k, *in));
        in = next;
      });
  }
  return part;
}

}  // namespace baker
