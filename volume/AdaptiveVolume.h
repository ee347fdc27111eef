#pragma once
#include <Eigen/Core>
#include <optional>
#include <vector>

#include "volume/LevelGrids.h"
#include "volume/PlacementSummary.h"
#include "volume/ProbeInterpolation.h"
#include "volume/Volume.h"

namespace baker {

// A volume baked with adaptive placement: levels of probes nested over one box (LevelGrids.h),
// coarsest first. Each level is a Volume on its own grid holding only some bricks (Volume::rows):
// those placed at that level (level 0: every brick but those deep inside closed geometry) that
// are worth storing (StoredBricks.h). The
// settings that made it are level 0's. A uniform bake is the case of one level.
struct AdaptiveVolume {
  std::vector<Volume> levels;
  int marginCells = kDefaultMarginCells;
  // On a shard's part (its levels' Volume::shard set): the whole bake's placement. Each level of
  // a part holds the bricks of the shard's share (shardLevelBricks), every probe traced but
  // border probes (Interpolated, values to come) and Invalid ones (unfilled): finishAdaptiveLevels
  // runs when the parts are merged.
  std::optional<PlacementSummary> placement;

  const Volume& coarsest() const { return levels.front(); }
};

// The level that serves a position, and its interpolation there: the finest of levels
// [0, levelCount) whose probes around the position are all held. Level 0 when none is (a
// point deep inside closed geometry, where level 0's bricks are not placed), incomplete:
// apply it renormalised.
struct LevelChoice {
  int level = 0;
  ProbeInterpolation interpolation;
};
LevelChoice finestLevelAt(const std::vector<Volume>& levels, int levelCount, const Eigen::Vector3d& world);

// The interpolated values of levels [0, levelCount) at `world`: what a decoder returns there
// (`skyDirect` and `skyBounced` too when given, for levels that keep them).
void sampleLevels(const std::vector<Volume>& levels, int levelCount, const Eigen::Vector3d& world, float* coefficients,
                  float* visibility, float* skyDirect = nullptr, float* skyBounced = nullptr);

}  // namespace baker
