#pragma once
#include <string>

#include "bake/Basis.h"
#include "bake/Volume.h"

namespace baker {

// Writes `volume` as an OpenVDB file: one grid per entry of coefficientGrids(basis), voxel
// (i,j,k) = probe (i,j,k), each grid's transform mapping index space to world space, and
// file metadata naming the basis and the grid layout. Nothing appears at `path` on failure.
void writeVdb(const Volume& volume, const Basis& basis, const std::string& path);

}  // namespace baker
