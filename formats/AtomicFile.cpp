#include "formats/AtomicFile.h"

#include <fmt/format.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

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

AtomicDirectory::AtomicDirectory(std::string finalPath, bool (*replaceable)(const std::string& path))
    : final_(std::move(finalPath)) {
  while (final_.size() > 1 && final_.back() == '/') final_.pop_back();
  if (final_.empty()) throw InputError("output path is empty");
  std::filesystem::path parent = std::filesystem::path(final_).parent_path();
  if (parent.empty()) parent = ".";
  std::error_code ec;
  if (!std::filesystem::is_directory(parent, ec))
    throw InputError(fmt::format("{}: output directory '{}' does not exist", final_, parent.string()));
  if (std::filesystem::exists(final_, ec) && !(std::filesystem::is_directory(final_, ec) && replaceable(final_)))
    throw InputError(fmt::format("{}: exists and is not a volume this tool wrote; not replacing it", final_));
  temporary_ = fmt::format("{}.tmp-{}", final_, ::getpid());
  std::filesystem::remove_all(temporary_, ec);
  if (!std::filesystem::create_directory(temporary_, ec))
    throw InputError(fmt::format("{}: cannot create '{}': {}", final_, temporary_, ec.message()));
}

AtomicDirectory::~AtomicDirectory() {
  if (!committed_) {
    std::error_code ec;
    std::filesystem::remove_all(temporary_, ec);
  }
}

void AtomicDirectory::writeFile(const std::string& name, const std::string& bytes) const {
  std::ofstream out(std::filesystem::path(temporary_) / name, std::ios::binary);
  out.write(bytes.data(), std::streamsize(bytes.size()));
  out.close();
  if (!out) throw InputError(fmt::format("{}: cannot write {}", final_, name));
}

bool directoryHolds(const std::string& directory, const std::string& name) {
  std::error_code ec;
  return std::filesystem::is_regular_file(std::filesystem::path(directory) / name, ec);
}

void AtomicDirectory::commit() {
  std::error_code ec;
  const std::string previous = fmt::format("{}.old-{}", final_, ::getpid());
  const bool replacing = std::filesystem::exists(final_, ec);
  if (replacing) std::filesystem::rename(final_, previous, ec);
  if (!ec) std::filesystem::rename(temporary_, final_, ec);
  if (ec) throw InputError(fmt::format("{}: cannot move the finished volume into place: {}", final_, ec.message()));
  committed_ = true;
  if (replacing) std::filesystem::remove_all(previous, ec);
}

}  // namespace baker
