#pragma once
#include <openvdb/openvdb.h>

#include "bake/Basis.h"
#include "bake/Volume.h"

namespace baker {

// The file-level metadata that makes a volume self-describing (keys "baker.*"); the
// reader recovers the grid placement and basis from it.
openvdb::MetaMap volumeMetadata(const Volume& volume, const Basis& basis);

}  // namespace baker
