#include "formats/VolumeReader.h"

#include <fmt/format.h>

#include <filesystem>

#include "basis/BasisRegistry.h"
#include "common/Error.h"
#include "formats/ExrSlices.h"
#include "formats/VdbReader.h"

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
  if (sharpness == volume.settings.end()) return makeBasis(volume.basisName);
  try {
    return makeBasis(volume.basisName, std::stod(sharpness->second));
  } catch (const std::logic_error&) {
    throw InputError(fmt::format("baker.setting.sg_sharpness \"{}\" is not a number", sharpness->second));
  }
}

}  // namespace baker
