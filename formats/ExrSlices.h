#pragma once
#include <string>

#include "basis/Basis.h"
#include "formats/VolumeHeader.h"
#include "volume/Volume.h"

namespace baker {

enum class ExrPrecision { Half, Float };

// A volume as EXR slices: a directory holding one multi-channel OpenEXR image per z slice
// (z0000.exr, …; pixel column i, row j = probe (i, j, k), row 0 first in the file) and
// manifest.json, which lists the slices and repeats the header. Slices rather than one
// multi-part file: each is an ordinary RGB-and-more image every EXR tool reads, and a slice is
// what an engine uploads as one layer of a 3D texture. Channels are named after the grids of
// volumeGrids ("rgb_00.R", "Y_03", "visibility_00", "probe_state", "probe_offset.X", …).
// Coefficients and visibility are stored in `precision`; probe states and offsets always in
// float. Half has no values above 65504: when a coefficient exceeds it, every coefficient is
// divided by a power of two, recorded as baker.coefficient_scale (multiply to decode).
// Nothing appears at `directory` on failure.
void writeExrSlices(const Volume& volume, const Basis& basis, const std::string& directory, ExrPrecision precision);

// Reads a directory written by writeExrSlices (or its manifest.json). InputError naming the
// file and what is missing or inconsistent.
Volume readExrSlices(const std::string& path, PartReading parts = PartReading::EveryProbe);

// Whether `path` is a directory with a manifest.json of EXR slices.
bool isExrSliceDirectory(const std::string& path);

}  // namespace baker
