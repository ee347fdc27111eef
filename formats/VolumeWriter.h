#pragma once
#include <string>

#include "basis/Basis.h"
#include "formats/ExrSlices.h"
#include "volume/Volume.h"

namespace baker {

enum class VolumeFormat { Vdb, Exr };

struct VolumeOutput {
  std::string path;
  VolumeFormat format = VolumeFormat::Vdb;
  ExrPrecision precision = ExrPrecision::Half;
};

// The output a bake's --out, --format and --precision describe: `--format` when given, else
// from the path (.vdb: OpenVDB; anything else, a directory of EXR slices); default path: the
// scene's stem with .vdb, or with _exr for slices. InputError for a contradiction.
VolumeOutput volumeOutput(const std::string& scenePath, std::string out, const std::string& format,
                          const std::string& precision);

void writeVolume(const Volume& volume, const Basis& basis, const VolumeOutput& output);

}  // namespace baker
