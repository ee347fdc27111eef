#pragma once
#include <cstddef>
#include <cstdint>
#include <string>

namespace baker::fuzz {

// A private temporary directory for one fuzzing process: the readers take paths, so every input
// is written to a file in it first. Removed when the process exits normally.
class FuzzDirectory {
 public:
  explicit FuzzDirectory(const std::string& target);
  ~FuzzDirectory();
  FuzzDirectory(const FuzzDirectory&) = delete;
  FuzzDirectory& operator=(const FuzzDirectory&) = delete;

  const std::string& path() const { return path_; }
  // Writes `size` bytes to NAME in the directory, replacing it; returns the file's path.
  std::string write(const std::string& name, const std::uint8_t* data, std::size_t size) const;

 private:
  std::string path_;
};

}  // namespace baker::fuzz
