#pragma once
#include <string>

#include "scene/Environment.h"
#include "volume/SkyRadiance.h"

namespace baker {

// The environment as a volume keeps it (volume/SkyRadiance.h): a map's texels, cut into cells no
// wider than half a record texel, each cell's flux added to the record texel its centre's world
// direction falls in; a constant sky in every texel; nothing as zeros. Serial and in texel order:
// the same bytes on any machine. InputError naming the map if a texel leaves single precision.
SkyRadiance recordSky(const Environment& environment);

// The environment as a volume's setting "sky" records it, the same on every machine: "none",
// "constant r,g,b", or "map NAME fnv1a64 HASH intensity K rotation D" (the file's name and the
// hash of its bytes, not its path).
std::string skyDescription(const Environment& environment);

}  // namespace baker
