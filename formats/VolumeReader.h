#pragma once
#include <string>

#include "bake/Volume.h"

namespace baker {

// Reads a volume written by this tool. Throws InputError naming the file and what is
// missing or inconsistent.
Volume readVolume(const std::string& path);

}  // namespace baker
