#pragma once
#include <string>

#include "basis/Basis.h"
#include "basis/StoredSignal.h"
#include "formats/EngineExport.h"
#include "volume/Volume.h"

namespace baker {

// three.js's LightProbeGrid, as three.js r187 (npm three@0.187.0) samples it: per probe the
// unconvolved radiance of spherical harmonics up to L2 (9 coefficients × RGB, three.js's
// SphericalHarmonics3 order, which is this project's), probes at the centres of the grid's
// cells. A directory holding
//  - light_probe_grid.json: the toJSON form of three.js PR #33658 (width, height, depth,
//    resolution, position = the box's centre, coefficients {scale, data: integers}), plus a
//    "baker" object with the volume's metadata that three.js ignores;
//  - light_probe_grid.bin: the half-float RGBA 3D atlas LightProbeGridWebGL samples, ready to be
//    a Data3DTexture (x fastest, then y, then 7 sub-volumes of nz + 2 layers).
// Only SH bases up to L2 convert exactly (threeJsRefusal). Nothing appears on failure.
EngineExport writeThreeJsProbeGrid(const Volume& volume, const Basis& basis, const std::string& directory);

// Why `basis` cannot be written for three.js exactly (which bases can), or "" when it can.
std::string threeJsRefusal(const Basis& basis);

// How `basis` becomes three.js's SH, in one sentence (the bake states it in its plan).
std::string threeJsConversion(const Basis& basis, StoredSignal signal);

// Reads such a directory (or its light_probe_grid.json) back as an sh-l2 irradiance volume:
// what three.js will shade with. InputError naming the file and field.
Volume readThreeJsProbeGrid(const std::string& path);

bool isThreeJsProbeGridDirectory(const std::string& path);

// three.js's atlas: sub-volumes of nz + 2 layers (a padding copy of the first and of the last
// slice around the data), each holding four of the 27 values.
constexpr int kThreeJsAtlasSubVolumes = 7;

}  // namespace baker
