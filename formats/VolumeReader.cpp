#include "formats/VolumeReader.h"

#include <fmt/format.h>

#include <filesystem>

#include "common/Error.h"
#include "formats/ExrSlices.h"
#include "formats/VdbReader.h"
#include "formats/VolumeHeader.h"

namespace baker {

Volume readVolume(const std::string& path) {
  std::error_code ec;
  const std::filesystem::path p(path);
  if (std::filesystem::is_directory(p, ec) || p.filename() == "manifest.json") return readExrSlices(path);
  if (!std::filesystem::is_regular_file(p, ec)) throw InputError(fmt::format("{}: volume file does not exist", path));
  return readVdb(path);
}

std::unique_ptr<Basis> basisOf(const Volume& volume) {
  const auto sharpness = volume.settings.find("sg_sharpness");
  if (sharpness == volume.settings.end()) return basisInFile(volume.basisName, std::nullopt, "baker.basis");
  double value = 0.0;
  try {
    value = std::stod(sharpness->second);
  } catch (const std::logic_error&) {
    throw InputError(fmt::format("baker.setting.sg_sharpness \"{}\" is not a number", sharpness->second));
  }
  // 0 was once written for "the measured default".
  return basisInFile(volume.basisName, value == 0.0 ? std::nullopt : std::optional<double>(value),
                     "baker.setting.sg_sharpness");
}

}  // namespace baker
