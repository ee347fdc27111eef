#include "common/FileHash.h"

#include <fmt/format.h>

#include <fstream>

#include "common/Error.h"
#include "common/Fnv1a64.h"

namespace baker {

std::string fileHash(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(fmt::format("{}: cannot read the file to hash it", path));
  Fnv1a64 hash;
  char buffer[1 << 16];
  while (in) {
    in.read(buffer, sizeof buffer);
    hash.add(buffer, std::size_t(in.gcount()));
  }
  return fmt::format("{:016x}", hash.value());
}

}  // namespace baker
