#pragma once
#include <string>
#include <utility>
#include <vector>

#include "formats/VolumeHeader.h"
#include "volume/AdaptiveVolume.h"
#include "volume/Volume.h"

namespace baker {

// Reads an OpenVDB volume written by writeVdb. InputError naming the file and what is missing
// or inconsistent. Use readVolume, which picks the reader from the path.
// An adaptive volume is refused (InputError): it has levels (readAdaptiveVdb).
Volume readVdb(const std::string& path, PartReading parts = PartReading::EveryProbe);

// Every level of a volume written by writeAdaptiveVdb, or the one level of a uniform volume.
AdaptiveVolume readAdaptiveVdb(const std::string& path);

// How many levels the file holds (baker.levels; 1 without it), from its metadata only.
int vdbLevelCount(const std::string& path);
// The file's "baker.*" metadata as text, read without its grids.
std::vector<std::pair<std::string, std::string>> vdbMetadataText(const std::string& path);

}  // namespace baker
