#include "formats/VolumeReader.h"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>

#include "common/Error.h"
#include "formats/BevyIrradianceVolume.h"
#include "formats/ExrLevels.h"
#include "formats/ExrSlices.h"
#include "formats/ThreeJsProbeGrid.h"
#include "formats/VdbReader.h"
#include "formats/VolumeHeader.h"
#include "formats/VolumeMetadata.h"

namespace baker {

std::string volumeFormatOf(const std::string& path) {
  std::error_code ec;
  const std::filesystem::path p(path);
  if (std::filesystem::is_directory(p, ec)) {
    if (isExrSliceDirectory(path)) return "exr";
    if (isBevyIrradianceVolumeDirectory(path)) return "bevy";
    if (isThreeJsProbeGridDirectory(path)) return "threejs";
    throw InputError(fmt::format("{}: a directory without manifest.json, irradiance_volume.json or "
                                 "light_probe_grid.json: not a volume this tool wrote",
                                 path));
  }
  const std::string name = p.filename().string();
  if (name == "manifest.json") return "exr";
  if (name == "irradiance_volume.ktx2" || name == "irradiance_volume.json") return "bevy";
  if (name == "light_probe_grid.json") return "threejs";
  if (!std::filesystem::is_regular_file(p, ec)) throw InputError(fmt::format("{}: volume file does not exist", path));
  return "vdb";
}

Volume readVolume(const std::string& path, PartReading parts) {
  const std::string format = volumeFormatOf(path);
  if (format == "exr") return readExrSlices(path, parts);
  if (format == "bevy") return readBevyIrradianceVolume(path);
  if (format == "threejs") return readThreeJsProbeGrid(path);
  return readVdb(path, parts);
}

int levelCountOf(const std::string& path) {
  const std::string format = volumeFormatOf(path);
  if (format == "vdb") return vdbLevelCount(path);
  if (format != "exr") return 1;
  const nlohmann::json manifest = readExrManifest(path);
  const auto levels = manifest.find(kLevelsManifestKey);
  return levels != manifest.end() && levels->is_array() ? std::max<int>(1, int(levels->size())) : 1;
}

DistanceGrids distanceGridsOf(const std::string& path) {
  const std::string format = volumeFormatOf(path);
  if (format == "vdb") return distanceGridsInFile(vdbMetadataText(path));
  if (format != "exr") return DistanceGrids::ScalarPerValue;  // an engine's export holds no map
  // A directory of levels has no "metadata" of its own, and its levels hold no map.
  const nlohmann::json manifest = readExrManifest(path);
  if (!manifest.contains("metadata")) return DistanceGrids::ScalarPerValue;
  try {
    return distanceGridsInFile(exrMetadataText(manifest.at("metadata")));
  } catch (const nlohmann::json::exception& e) {
    throw InputError(fmt::format("{}: \"metadata\": {}", path, oneLine(e.what())));
  }
}

AdaptiveVolume readLevels(const std::string& path) {
  const std::string format = volumeFormatOf(path);
  if (format == "vdb") return readAdaptiveVdb(path);
  if (format == "exr") return readAdaptiveExrSlices(path);
  AdaptiveVolume volume;
  volume.levels.push_back(readVolume(path));
  return volume;
}

std::unique_ptr<Basis> basisOf(const Volume& volume) {
  return basisInFile(volume.basisName, volume.settings, "");
}

}  // namespace baker
