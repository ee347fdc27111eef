#pragma once
#include <vector>

#include "volume/ProbeGrid.h"

namespace baker {

// An adaptive volume nests levels of probes. The finest is laid out over the scene as a uniform
// grid at its spacing would be (makeProbeGrid: probes half a cell inside a closed room's walls);
// each coarser level has cells kLevelRatio times as wide, whole ones over the finer level's, each
// with its probe at the centre of its middle finer cell. Because the ratio is odd, every probe of
// a level sits exactly on a probe of the next finer level, so a level's interpolation is
// reproduced exactly by the finer level's probes set to it (docs/ADAPTIVE.md). Engines subdivide
// by 3 for the same reason (Unity's Adaptive Probe Volumes).
constexpr int kLevelRatio = 3;
constexpr int kMaxLevels = 4;
// A brick of a finer level is placed when geometry lies within its probes' box grown by this
// many of its cells: at least one, so that a surface between two bricks' probes marks both.
constexpr int kDefaultMarginCells = 1;
constexpr int kMinMarginCells = 1;
constexpr int kMaxMarginCells = 4;

// A level's grid may span at most this many probes, placed or not: a level holding only some
// bricks indexes every brick of its grid (8 bytes each).
constexpr double kMaxLevelGridProbes = 8.0 * 1024 * 1024 * 1024;
// ...and at most this many bricks (the index of a level holding some costs 8 bytes per brick).
constexpr double kMaxLevelBricks = 128.0 * 1024 * 1024;

// The grids of `levels` levels whose finest is `finest`, coarsest first.
std::vector<ProbeGrid> levelGrids(const ProbeGrid& finest, int levels);

// Whether `coarse` is laid out on `fine`'s lattice as levelGrids lays it out: spacing 3 times
// fine's, every probe on a probe of fine's lattice. What a reader checks of a file's levels.
bool nestsIn(const ProbeGrid& fine, const ProbeGrid& coarse);


}  // namespace baker
