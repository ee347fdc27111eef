#pragma once
#include <string>

#include "basis/Basis.h"
#include "volume/Volume.h"

namespace baker {

// Writes `volume` as an OpenVDB file: one grid per entry of volumeGrids (Vec3s for three
// components, float for one, int32 for probe_state), voxel (i,j,k) = probe (i,j,k), each
// grid's transform mapping index space to world space. Sparse: bricks (leaves) without a
// single valid probe are not stored. Grids are built and written one at a time, and the file
// is the one OpenVDB's own writer makes of them. Nothing appears at `path` on failure.
void writeVdb(const Volume& volume, const Basis& basis, const std::string& path);

}  // namespace baker
