#include "formats/VolumeWriter.h"

#include <fmt/format.h>

#include <filesystem>

#include "common/Error.h"
#include "formats/AtomicFile.h"
#include "formats/VdbWriter.h"

namespace baker {

VolumeOutput volumeOutput(const std::string& scenePath, std::string out, const std::string& format,
                          const std::string& precision) {
  VolumeOutput o;
  const bool vdbPath = std::filesystem::path(out).extension() == ".vdb";
  if (format == "vdb" || (format.empty() && (out.empty() || vdbPath)))
    o.format = VolumeFormat::Vdb;
  else if (format == "exr" || format.empty())
    o.format = VolumeFormat::Exr;
  else
    throw SettingError("format", fmt::format("{}: expected vdb or exr", format));
  if (o.format == VolumeFormat::Exr && vdbPath)
    throw SettingError("out", fmt::format("{}: a .vdb name for EXR slices; give a directory name", out));
  if (precision == "half")
    o.precision = ExrPrecision::Half;
  else if (precision == "float")
    o.precision = ExrPrecision::Float;
  else
    throw SettingError("precision", fmt::format("{}: expected half or float", precision));
  const std::string stem = std::filesystem::path(scenePath).stem().string();
  o.path = !out.empty() ? out : o.format == VolumeFormat::Vdb ? stem + ".vdb" : stem + "_exr";
  if (o.format == VolumeFormat::Vdb) {
    requireOutputDirectory(o.path);
  } else {
    std::filesystem::path parent = std::filesystem::path(o.path).parent_path();
    std::error_code ec;
    if (!parent.empty() && !std::filesystem::is_directory(parent, ec))
      throw InputError(fmt::format("{}: output directory '{}' does not exist", o.path, parent.string()));
    if (std::filesystem::exists(o.path, ec) && !isExrSliceDirectory(o.path))
      throw InputError(fmt::format("{}: exists and is not a volume this tool wrote; not replacing it", o.path));
  }
  return o;
}

void writeVolume(const Volume& volume, const Basis& basis, const VolumeOutput& output) {
  if (output.format == VolumeFormat::Vdb)
    writeVdb(volume, basis, output.path);
  else
    writeExrSlices(volume, basis, output.path, output.precision);
}

}  // namespace baker
