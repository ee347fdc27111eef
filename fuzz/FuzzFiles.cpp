#include "fuzz/FuzzFiles.h"

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <vector>

namespace baker::fuzz {

FuzzDirectory::FuzzDirectory(const std::string& target) {
  std::string pattern = (std::filesystem::temp_directory_path() / ("baker-fuzz-" + target + "-XXXXXX")).string();
  std::vector<char> buffer(pattern.begin(), pattern.end());
  buffer.push_back('\0');
  if (!mkdtemp(buffer.data())) throw std::runtime_error("cannot create a directory for " + pattern);
  path_ = buffer.data();
}

FuzzDirectory::~FuzzDirectory() {
  std::error_code ignored;
  std::filesystem::remove_all(path_, ignored);
}

std::string FuzzDirectory::write(const std::string& name, const std::uint8_t* data, std::size_t size) const {
  const std::string file = path_ + "/" + name;
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), std::streamsize(size));
  if (!out) throw std::runtime_error("cannot write " + file);
  return file;
}

}  // namespace baker::fuzz
