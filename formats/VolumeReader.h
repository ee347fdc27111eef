#pragma once
#include <memory>
#include <string>

#include "basis/Basis.h"
#include "formats/VolumeHeader.h"
#include "formats/VolumeLayout.h"
#include "volume/AdaptiveVolume.h"
#include "volume/Volume.h"

namespace baker {

// Reads a volume written by this tool, whatever the format: an OpenVDB file, a directory of
// EXR slices (or its manifest.json), or an engine's export (Bevy's irradiance volume, three.js's
// light probe grid: what the engine will shade with, in the basis it holds). The one reader
// every command uses. Throws InputError naming the file and what is missing or inconsistent.
// `parts`: how much of a shard's part to hold (VolumeHeader.h).
Volume readVolume(const std::string& path, PartReading parts = PartReading::EveryProbe);

// Every level of an adaptive volume (an OpenVDB file written by writeAdaptiveVdb), or the one
// level of a uniform volume in any format readVolume reads.
AdaptiveVolume readLevels(const std::string& path);
// How many levels the volume at `path` holds, from its metadata or manifest only: 1 for a
// uniform volume.
int levelCountOf(const std::string& path);

// How the volume at `path` holds its distance map (DistanceGrids, VolumeLayout.h), from its
// metadata or manifest only: what its grids are named in the file.
DistanceGrids distanceGridsOf(const std::string& path);

// Which format `path` holds, by its name or the files in its directory: "vdb", "exr", "bevy",
// "threejs". InputError for a directory of none of them or a missing file.
std::string volumeFormatOf(const std::string& path);

// The basis a volume was baked in, with the settings that shape it (an sg-N bake's sharpness).
std::unique_ptr<Basis> basisOf(const Volume& volume);

}  // namespace baker
