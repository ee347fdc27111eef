#include "formats/VolumeWriter.h"

#include <fmt/format.h>

#include <filesystem>

#include "basis/BasisRegistry.h"
#include "common/Error.h"
#include "formats/AtomicFile.h"
#include "formats/BevyIrradianceVolume.h"
#include "formats/ExrLevels.h"
#include "formats/ThreeJsProbeGrid.h"
#include "formats/VdbWriter.h"

namespace baker {
namespace {

struct FormatEntry {
  VolumeFormat format;
  const char* name;
  const char* directorySuffix;  // of the default path
  bool (*isOurs)(const std::string& path);
};

const FormatEntry kFormats[] = {
    {VolumeFormat::Vdb, "vdb", "", nullptr},
    {VolumeFormat::Exr, "exr", "_exr", isExrSliceDirectory},
    {VolumeFormat::Bevy, "bevy", "_bevy", isBevyIrradianceVolumeDirectory},
    {VolumeFormat::ThreeJs, "threejs", "_threejs", isThreeJsProbeGridDirectory},
};

const FormatEntry& entryOf(VolumeFormat format) {
  for (const FormatEntry& e : kFormats)
    if (e.format == format) return e;
  return kFormats[0];
}

}  // namespace

const char* volumeFormatName(VolumeFormat format) { return entryOf(format).name; }

VolumeOutput volumeOutput(const std::string& scenePath, std::string out, const std::string& format,
                          const std::string& precision) {
  VolumeOutput o;
  const bool vdbPath = std::filesystem::path(out).extension() == ".vdb";
  if (format.empty()) {
    o.format = out.empty() || vdbPath ? VolumeFormat::Vdb : VolumeFormat::Exr;
  } else {
    const FormatEntry* named = nullptr;
    for (const FormatEntry& e : kFormats)
      if (format == e.name) named = &e;
    if (!named) throw SettingError("format", fmt::format("{}: expected vdb, exr, bevy or threejs", format));
    o.format = named->format;
  }
  if (o.format != VolumeFormat::Vdb && vdbPath)
    throw SettingError("out", fmt::format("{}: a .vdb name for {}, which is a directory; give a directory name", out,
                                          volumeFormatName(o.format)));
  if (precision == "half")
    o.precision = ExrPrecision::Half;
  else if (precision == "float")
    o.precision = ExrPrecision::Float;
  else
    throw SettingError("precision", fmt::format("{}: expected half or float", precision));
  const FormatEntry& entry = entryOf(o.format);
  const std::string stem = std::filesystem::path(scenePath).stem().string();
  o.path = !out.empty() ? out : o.format == VolumeFormat::Vdb ? stem + ".vdb" : stem + entry.directorySuffix;
  if (o.format == VolumeFormat::Vdb) {
    requireOutputDirectory(o.path);
  } else {
    std::filesystem::path parent = std::filesystem::path(o.path).parent_path();
    std::error_code ec;
    if (!parent.empty() && !std::filesystem::is_directory(parent, ec))
      throw InputError(fmt::format("{}: output directory '{}' does not exist", o.path, parent.string()));
    if (std::filesystem::exists(o.path, ec) && !entry.isOurs(o.path))
      throw InputError(fmt::format("{}: exists and is not a {} volume this tool wrote; not replacing it", o.path,
                                   entry.name));
  }
  return o;
}

std::string preferredBasis(const VolumeOutput& output) {
  return output.format == VolumeFormat::Bevy ? "ambient-cube" : "";
}

bool prefersNonNegativeFit(const VolumeOutput& output, const Basis& basis) {
  return output.format == VolumeFormat::Bevy && admitsNonNegativeFit(basis);
}

void requireWritable(const VolumeOutput& output, const Basis& basis) {
  const bool engine = output.format == VolumeFormat::Bevy || output.format == VolumeFormat::ThreeJs;
  if (engine && basis.hemisphere())
    throw SettingError("basis", fmt::format("{} cannot be written to format {}: it holds radiance over one hemisphere, "
                                            "and an engine's volume needs irradiance for every normal; write vdb or exr",
                                            basis.name(), volumeFormatName(output.format)));
  if (output.format != VolumeFormat::ThreeJs) return;
  if (const std::string refusal = threeJsRefusal(basis); !refusal.empty())
    throw SettingError("basis", fmt::format("{} cannot be written to format {} exactly: {}; formats vdb, exr and bevy "
                                            "take every basis",
                                            basis.name(), volumeFormatName(output.format), refusal));
}

std::string volumeConversion(const VolumeOutput& output, const Basis& basis, StoredSignal signal) {
  switch (output.format) {
    case VolumeFormat::Bevy: return bevyConversion(basis, signal);
    case VolumeFormat::ThreeJs: return threeJsConversion(basis, signal);
    default: return "";
  }
}

EngineExport writeVolume(const Volume& volume, const Basis& basis, const VolumeOutput& output) {
  // An engine's files hold a whole volume; a part keeps only its bricks, which vdb and exr store.
  if (volume.shard && (output.format == VolumeFormat::Bevy || output.format == VolumeFormat::ThreeJs))
    throw SettingError("format", fmt::format("{}: a shard's part is written as vdb or exr; the merged volume can be "
                                             "written in an engine's format",
                                             volumeFormatName(output.format)));
  switch (output.format) {
    case VolumeFormat::Vdb: writeVdb(volume, basis, output.path); return {};
    case VolumeFormat::Exr: writeExrSlices(volume, basis, output.path, output.precision); return {};
    case VolumeFormat::Bevy: return writeBevyIrradianceVolume(volume, basis, output.path);
    case VolumeFormat::ThreeJs: return writeThreeJsProbeGrid(volume, basis, output.path);
  }
  return {};
}

void requireLevelsWritable(const VolumeOutput& output, int levels) {
  if (levels > 1 && output.format != VolumeFormat::Vdb && output.format != VolumeFormat::Exr)
    throw SettingError("format", fmt::format("{}: an adaptive volume's levels are written to a .vdb file or EXR slices "
                                             "only, so far (docs/ADAPTIVE.md)",
                                             volumeFormatName(output.format)));
}

EngineExport writeLevels(const AdaptiveVolume& volume, const Basis& basis, const VolumeOutput& output) {
  if (volume.placement && output.format != VolumeFormat::Vdb)
    throw SettingError("format", fmt::format("{}: a shard's part of an adaptive bake is written to a .vdb file only",
                                             volumeFormatName(output.format)));
  if (volume.levels.size() == 1 && !volume.placement) return writeVolume(volume.levels.front(), basis, output);
  requireLevelsWritable(output, int(volume.levels.size()));
  if (output.format == VolumeFormat::Exr)
    writeAdaptiveExrSlices(volume, basis, output.path, output.precision);
  else
    writeAdaptiveVdb(volume, basis, output.path);
  return {};
}

}  // namespace baker
