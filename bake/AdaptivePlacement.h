#pragma once
#include <cstdint>
#include <vector>

#include "scene/RayTracer.h"
#include "scene/Scene.h"
#include "volume/LevelGrids.h"
#include "volume/ProbeGrid.h"
#include "volume/ProbeRows.h"

namespace baker {

// Where the probes of an adaptive bake go (volume/LevelGrids.h), decided from the scene's
// geometry before anything is traced:
//  - level 0 places every brick but those deep inside closed geometry: no triangle lies within
//    the brick or within `marginCells` + 1 cells of it, and from its centre nearly every direction meets a back face
//    (kDeepInsideBackfaceRatio), so every probe of it is inside a solid, one cell or more from
//    its surface;
//  - a finer level places a sub-brick of 4³ probes (volume/SubBricks.h) when a triangle lies
//    within the box of its probes grown by `marginCells` + 1 of its cells (an exact
//    triangle–box test), so probes are dense where light changes (near surfaces) and sparse in
//    open air; a brick is placed when one of its sub-bricks is. The extra cell places every
//    neighbour of a probe within `marginCells` of a surface, so that probe is traced, not on the
//    level's border.
struct AdaptivePlacement {
  std::vector<ProbeGrid> grids;                   // coarsest first
  std::vector<std::vector<std::int64_t>> bricks;  // per level, the bricks placed, by increasing index
  std::vector<std::vector<std::uint8_t>> masks;   // per level and placed brick, its sub-bricks placed
  int marginCells = kDefaultMarginCells;
  std::int64_t deepInsideBricks = 0;  // of level 0, not placed

  int levels() const { return int(grids.size()); }
  std::int64_t probes(int level) const;  // placed at one level
  std::int64_t probes() const;           // placed at every level
  // The probes placed at `level`: every placed brick, or those of `share` (placed bricks).
  ProbeRows rows(int level) const;
  ProbeRows rows(int level, const std::vector<std::int64_t>& share) const;
};

// From nearly every direction a back face: what "deep inside closed geometry" means here
// (ProbeValidity's ratio, stricter than its 0.25 for moving a probe, because a brick not placed
// has nothing to fall back on).
constexpr float kDeepInsideBackfaceRatio = 0.9f;

// Places the bricks of `levels` levels whose finest is `finest` (levelGrids). SettingError("spacing")
// when the placed probes are beyond `maxProbes`.
AdaptivePlacement placeAdaptive(const Scene& scene, const RayTracer& tracer, const ProbeGrid& finest, int levels,
                                int marginCells, std::int64_t maxProbes);

}  // namespace baker
