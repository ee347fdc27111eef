#pragma once
#include <string>

#include "basis/Basis.h"
#include "basis/StoredSignal.h"
#include "formats/EngineExport.h"
#include "formats/ExrSlices.h"
#include "volume/AdaptiveVolume.h"
#include "volume/Volume.h"

namespace baker {

// baker's own formats (vdb, exr), and engines' own (bevy: Bevy's IrradianceVolume; threejs:
// three.js's LightProbeGrid), each a directory of its files.
enum class VolumeFormat { Vdb, Exr, Bevy, ThreeJs };

const char* volumeFormatName(VolumeFormat format);

struct VolumeOutput {
  std::string path;
  VolumeFormat format = VolumeFormat::Vdb;
  ExrPrecision precision = ExrPrecision::Half;
};

// The output a bake's --out, --format and --precision describe: `--format` when given, else
// from the path (.vdb: OpenVDB; anything else, a directory of EXR slices); default path: the
// scene's stem with .vdb, or with _exr, _bevy or _threejs for a directory. InputError for a
// contradiction, or for an existing path that is not a volume of that format.
VolumeOutput volumeOutput(const std::string& scenePath, std::string out, const std::string& format,
                          const std::string& precision);

// The basis an output takes when none is asked for ("" for the bake's own default): Bevy stores
// an ambient cube, so an ambient-cube bake is stored without conversion.
std::string preferredBasis(const VolumeOutput& output);

// Whether a bake for this output should solve for coefficients >= 0: RGB9E5 (bevy) holds no
// negative value, and where the basis's functions are all >= 0 such a fit needs no clamping
// (a linear ambient-cube fit of the bundled room dips below zero on 99 of its 864 face values).
bool prefersNonNegativeFit(const VolumeOutput& output, const Basis& basis);

// Checked before baking: SettingError naming the basis and the formats that take it when `basis`
// cannot be written to the output's format exactly.
void requireWritable(const VolumeOutput& output, const Basis& basis);

// How the output's format will hold `basis`, in one sentence; "" for baker's own formats, which
// store it as it is.
std::string volumeConversion(const VolumeOutput& output, const Basis& basis, StoredSignal signal);

// Writes the volume; for an engine's format, returns what the conversion did.
EngineExport writeVolume(const Volume& volume, const Basis& basis, const VolumeOutput& output);

// Checked before baking: SettingError("format") when the output cannot hold `levels` levels.
void requireLevelsWritable(const VolumeOutput& output, int levels);
// Writes every level (writeAdaptiveVdb), or the one level of a uniform volume as writeVolume does.
EngineExport writeLevels(const AdaptiveVolume& volume, const Basis& basis, const VolumeOutput& output);

}  // namespace baker
