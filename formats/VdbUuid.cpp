#include "formats/VdbUuid.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstdint>
#include <fstream>
#include <stdexcept>
#include <vector>

namespace baker {
namespace {

// Archive::writeHeader: magic (8 bytes), file format version (4), library major and minor
// version (4 + 4), "has grid offsets" (1), then the UUID as 36 characters.
constexpr std::uint64_t kUuidOffset = 21;
constexpr std::size_t kUuidLength = 36;

bool looksLikeUuid(const char* text) {
  for (std::size_t i = 0; i < kUuidLength; ++i) {
    const char c = text[i];
    const bool dash = i == 8 || i == 13 || i == 18 || i == 23;
    if (dash ? c != '-' : !((c >= '0' && c <= '9') || (c >= 'a' && c <= 'f') || (c >= 'A' && c <= 'F'))) return false;
  }
  return true;
}

}  // namespace

void deriveVdbUuid(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(fmt::format("{}: cannot reopen the written file to set its UUID", path));
  std::vector<char> buffer(1 << 16);
  in.read(buffer.data(), std::streamsize(kUuidOffset + kUuidLength));
  if (std::size_t(in.gcount()) != kUuidOffset + kUuidLength || !looksLikeUuid(buffer.data() + kUuidOffset))
    throw std::runtime_error(fmt::format("{}: the written file has no UUID where OpenVDB writes one", path));

  // Two FNV-1a hashes with different offset bases: 128 bits, of which the UUID keeps 122.
  std::uint64_t first = 0xcbf29ce484222325ull, second = 0x84222325cbf29ce4ull;
  constexpr std::uint64_t kPrime = 0x100000001b3ull;
  in.clear();
  in.seekg(0);
  std::uint64_t position = 0;
  while (in) {
    in.read(buffer.data(), std::streamsize(buffer.size()));
    const std::size_t count = std::size_t(in.gcount());
    // The UUID's bytes in this piece, if any, read as '0': [from, to).
    const std::uint64_t from = std::max(kUuidOffset, position), to = std::min(kUuidOffset + kUuidLength, position + count);
    if (from < to) std::fill(buffer.begin() + std::ptrdiff_t(from - position), buffer.begin() + std::ptrdiff_t(to - position), '0');
    for (std::size_t i = 0; i < count; ++i) {
      const unsigned char byte = static_cast<unsigned char>(buffer[i]);
      first = (first ^ byte) * kPrime;
      second = (second ^ byte) * kPrime;
    }
    position += count;
  }
  in.close();

  std::string hex = fmt::format("{:016x}{:016x}", first, second);
  hex[12] = '8';                                           // version 8: custom
  hex[16] = "89ab"[(second >> 62) & 3];                    // variant 10xx
  const std::string uuid = fmt::format("{}-{}-{}-{}-{}", hex.substr(0, 8), hex.substr(8, 4), hex.substr(12, 4),
                                       hex.substr(16, 4), hex.substr(20, 12));
  std::fstream out(path, std::ios::binary | std::ios::in | std::ios::out);
  out.seekp(std::streamoff(kUuidOffset));
  out.write(uuid.data(), std::streamsize(kUuidLength));
  out.close();
  if (!out) throw std::runtime_error(fmt::format("{}: cannot write the file's UUID", path));
}

}  // namespace baker
