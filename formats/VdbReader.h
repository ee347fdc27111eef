#pragma once
#include <string>

#include "formats/VolumeHeader.h"
#include "volume/Volume.h"

namespace baker {

// Reads an OpenVDB volume written by writeVdb. InputError naming the file and what is missing
// or inconsistent. Use readVolume, which picks the reader from the path.
Volume readVdb(const std::string& path, PartReading parts = PartReading::EveryProbe);

}  // namespace baker
