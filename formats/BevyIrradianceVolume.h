#pragma once
#include <string>

#include "basis/Basis.h"
#include "basis/StoredSignal.h"
#include "formats/EngineExport.h"
#include "volume/Volume.h"

namespace baker {

// Bevy's IrradianceVolume (bevy_light, Bevy 0.13 to 0.19): a directory holding
//  - irradiance_volume.ktx2: Bevy's ambient-cube 3D texture in RGB9E5, the texel format Bevy's
//    own exporter writes. For probes (Rx, Ry, Rz) it is Rx × 2Ry × 3Rz; face F of probe (i, j, k)
//    sits at (i, j + Ry·[F negative], k + Rz·axis(F)): positive faces in the lower half, as
//    Bevy's shader reads them (its doc comment says the opposite). Each face holds E(F)/π,
//    which Bevy multiplies by the component's intensity and the surface's diffuse colour;
//  - irradiance_volume.json: the Transform that maps Bevy's unit cube onto the probe grid (probes
//    at cell centres), the intensity that makes the values the scene's radiance, and the
//    volume's metadata.
// Every basis converts: an ambient-cube bake as it is; any other by its irradiance at the six
// axes. RGB9E5 holds 0 … 65408: values outside are clamped and counted.
EngineExport writeBevyIrradianceVolume(const Volume& volume, const Basis& basis, const std::string& directory);

// How `basis` becomes Bevy's ambient cube, in one sentence (the bake states it in its plan).
std::string bevyConversion(const Basis& basis, StoredSignal signal);

// Reads such a directory (or its .ktx2) back as an ambient-cube volume: what Bevy shades with.
// InputError naming the file and field.
Volume readBevyIrradianceVolume(const std::string& path);

bool isBevyIrradianceVolumeDirectory(const std::string& path);

}  // namespace baker
