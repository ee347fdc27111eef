#include "tests/TestData.h"

#include <unistd.h>

#include <filesystem>

namespace baker::test {

std::string sourcePath(const std::string& relative) { return std::string(BAKER_SOURCE_DIR) + "/" + relative; }

std::string sharedDataPath(const std::string& relative) {
  const std::filesystem::path root = std::filesystem::path(BAKER_SOURCE_DIR).parent_path() / "shared" / "data";
  std::error_code ec;
  if (!std::filesystem::is_directory(root, ec)) return "";
  return (root / relative).string();
}

std::string makeTempDir(const std::string& name) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / ("baker-test-" + name + "-" +
                                                                             std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir.string();
}

}  // namespace baker::test
