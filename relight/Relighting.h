#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "basis/Basis.h"
#include "formats/EngineExport.h"
#include "formats/VolumeWriter.h"
#include "scene/SceneOptions.h"
#include "volume/AdaptiveVolume.h"
#include "volume/SkyHarmonics.h"
#include "volume/SkyRadiance.h"

namespace baker {

// `baker relight`: a baked volume under another sky, without tracing a ray.
struct RelightRequest {
  std::string volumePath;
  // The new sky: environmentMap (with its intensity and rotation) or a constant `sky`; the glTF
  // scene index is not read. A constant sky of 0,0,0 leaves the light that is not the sky's.
  SceneOptions sky;
  VolumeOutput output;
};

struct RelightReport {
  std::string basis, signal;
  int levels = 1;
  std::int64_t probes = 0;      // held, over every level
  std::string fromSky, toSky;   // the settings "sky" before and after
  std::string bakedSky;         // the sky the bake traced (setting "baked_sky" once relit)
  int bounces = 0;              // of the bake
  bool otherLights = false;     // whether the bake had lights besides the sky (lamps, emission)
  std::string visibility;       // how V(ω) was read (SkyTransfer::visibilitySource)
  std::string oldSkyRemoved;    // how the old sky's direct light was taken away (SkyChange)
  bool bounceScaled = false;    // whether its light off surfaces was scaled to the new sky (SkyChange)
  std::vector<std::string> changes, keeps;  // in words, what the relit volume changes and keeps
  std::vector<std::string> warnings;        // e.g. texels of the new map that were not finite
  EngineExport engineExport;
  double seconds = 0.0;
};

// How a relighting read the volume, in words for reports.
struct SkyChange {
  std::string visibility;     // how V(ω) was read (SkyTransfer::visibilitySource)
  std::string oldSkyRemoved;  // exactly (from Volume::skyDirect) or through the visibility
  // Whether the sky's light off surfaces (Volume::skyBounced) was scaled to the new sky: with
  // skyDirect, skyBounced and distance maps; otherwise it stays as baked.
  bool bounceScaled = false;
};

// Relights every probe of `volume` (each level) to `sky`, and records it (setting "sky":
// `description`; "baked_sky" keeps the sky the bake traced). Where the volume keeps each probe's
// directly seen sky (Volume::skyDirect), that part is replaced by `sky` seen through the stored
// visibility (volume/SkyTransfer.h), and kept as skyDirect, so that relit volumes relight again
// alike; otherwise the change from the recorded sky to `sky` is added through the visibility.
// Where it also keeps the sky's light off surfaces (Volume::skyBounced) and distance maps, that
// part is scaled per probe by the new sky's flux through the probe's map over the old one's.
// InputError when the volume holds no visibility or records no sky; NumericalError if a value
// would leave single precision.
SkyChange relightVolume(AdaptiveVolume& volume, const Basis& basis, const SkyRadiance& sky,
                        const std::string& description, const std::string& name);

// The sky `options` name (an environment map or a constant sky) as decoders take it at run time,
// with its description as the setting "sky" gives it; `warnings` hears about texels read as 0.
struct DescribedSkyHarmonics {
  SkyHarmonics harmonics;
  std::string description;
};
DescribedSkyHarmonics skyHarmonicsOf(const SceneOptions& options, std::vector<std::string>& warnings);

// Reads the volume, relights it to the request's sky and writes it to the output (atomically:
// nothing is written on an error). SettingError "env" when the request names no sky.
RelightReport relightVolumeFile(const RelightRequest& request);

}  // namespace baker
