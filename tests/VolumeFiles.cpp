#include "tests/VolumeFiles.h"

#include <gtest/gtest.h>

#include <fstream>
#include <iterator>

namespace baker::test {

namespace fs = std::filesystem;

std::string bytesOf(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

std::map<std::string, std::string> filesOf(const fs::path& volume) {
  if (fs::is_regular_file(volume)) return {{"", bytesOf(volume)}};
  std::map<std::string, std::string> files;
  for (const auto& entry : fs::recursive_directory_iterator(volume))
    if (entry.is_regular_file()) files[fs::relative(entry.path(), volume).string()] = bytesOf(entry.path());
  return files;
}

void expectSameFiles(const fs::path& volume, const fs::path& expected) {
  const auto a = filesOf(volume), b = filesOf(expected);
  ASSERT_EQ(a.size(), b.size()) << volume << " against " << expected;
  for (auto i = a.begin(), j = b.begin(); i != a.end(); ++i, ++j) {
    EXPECT_EQ(i->first, j->first);
    EXPECT_TRUE(i->second == j->second) << i->first << " of " << volume << " differs from " << expected;
  }
}

}  // namespace baker::test
