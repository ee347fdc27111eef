#include "formats/AtomicFile.h"

#include <fmt/format.h>
#include <unistd.h>

#include <filesystem>

#include "common/Error.h"

namespace baker {

void requireOutputDirectory(const std::string& path) {
  if (path.empty()) throw InputError("output path is empty");
  std::filesystem::path dir = std::filesystem::path(path).parent_path();
  if (dir.empty()) dir = ".";
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec))
    throw InputError(fmt::format("{}: output directory '{}' does not exist", path, dir.string()));
  if (std::filesystem::is_directory(path, ec))
    throw InputError(fmt::format("{}: output path is a directory", path));
}

AtomicFile::AtomicFile(std::string finalPath) : final_(std::move(finalPath)) {
  requireOutputDirectory(final_);
  // Same directory, so the final rename stays on one file system and is atomic.
  temporary_ = fmt::format("{}.tmp-{}", final_, ::getpid());
}

AtomicFile::~AtomicFile() {
  if (!committed_) {
    std::error_code ec;
    std::filesystem::remove(temporary_, ec);
  }
}

void AtomicFile::commit() {
  std::error_code ec;
  std::filesystem::rename(temporary_, final_, ec);
  if (ec) throw InputError(fmt::format("{}: cannot move the finished file into place: {}", final_, ec.message()));
  committed_ = true;
}

}  // namespace baker
