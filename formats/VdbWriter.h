#pragma once
#include <string>

#include "basis/Basis.h"
#include "volume/AdaptiveVolume.h"
#include "volume/Volume.h"

namespace baker {

// Writes `volume` as an OpenVDB file: one grid per entry of volumeGrids (Vec3s for three
// components, float for one, int32 for probe_state), voxel (i,j,k) = probe (i,j,k) (N² voxels a
// probe in the distance atlas), each grid's transform mapping index space to world space. Sparse:
// only the bricks (leaves) that storedBricks keeps. Grids are built and written a batch at a
// time, and the file is the one OpenVDB's own writer makes of them. Nothing appears at `path` on
// failure.
void writeVdb(const Volume& volume, const Basis& basis, const std::string& path);

// Writes every level of an adaptive volume to one OpenVDB file (docs/FORMAT.md, "Levels"):
// level 0's grids under the names writeVdb uses and its metadata; level k's grids under
// levelGridPrefix(k) with their own transform, each holding exactly the bricks the level holds; "baker.levels", "baker.level_ratio", "baker.margin_cells" and per finer level
// "baker.levelK.dims", ".origin", ".spacing".
void writeAdaptiveVdb(const AdaptiveVolume& volume, const Basis& basis, const std::string& path);

}  // namespace baker
