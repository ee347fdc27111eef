#pragma once
#include <memory>
#include <string>

#include "basis/Basis.h"
#include "volume/Volume.h"

namespace baker {

// Reads a volume written by this tool, whatever the format: an OpenVDB file, or a directory
// of EXR slices (or its manifest.json). The one reader every command uses. Throws InputError
// naming the file and what is missing or inconsistent.
Volume readVolume(const std::string& path);

// The basis a volume was baked in, with the settings that shape it (an sg-N bake's sharpness).
std::unique_ptr<Basis> basisOf(const Volume& volume);

}  // namespace baker
