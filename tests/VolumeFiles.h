#pragma once
#include <filesystem>
#include <map>
#include <string>

namespace baker::test {

// A file's bytes ("" when it cannot be read).
std::string bytesOf(const std::filesystem::path& file);
// Every file of a volume (one .vdb, or a directory of EXR slices or an engine's files, level
// directories included) by its path inside the volume ("" for a single file), with its bytes.
std::map<std::string, std::string> filesOf(const std::filesystem::path& volume);
// The two volumes are the same files with the same bytes (a gtest failure naming the first that differs).
void expectSameFiles(const std::filesystem::path& volume, const std::filesystem::path& expected);

}  // namespace baker::test
