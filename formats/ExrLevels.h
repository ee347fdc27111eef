#pragma once
#include <string>

#include "basis/Basis.h"
#include "formats/ExrSlices.h"
#include "volume/AdaptiveVolume.h"

namespace baker {

// An adaptive volume as EXR slices: a directory whose manifest.json lists its levels (coarsest
// first), each a slice set in its own directory level0/, level1/, … whose slices pack the
// level's bricks into an atlas (BrickAtlas.h; the manifest's "atlas" lists which brick each slot
// holds). docs/FORMAT.md "Levels". Nothing appears at `directory` on failure.
void writeAdaptiveExrSlices(const AdaptiveVolume& volume, const Basis& basis, const std::string& directory,
                            ExrPrecision precision);

// Reads every level of a directory written by writeAdaptiveExrSlices (or its manifest.json), or
// the one level of a uniform EXR slice volume. InputError naming the file and what is wrong.
AdaptiveVolume readAdaptiveExrSlices(const std::string& path);

}  // namespace baker
