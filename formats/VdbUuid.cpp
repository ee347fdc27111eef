#include "formats/VdbUuid.h"

#include <fmt/format.h>

#include <cstdint>
#include <fstream>
#include <stdexcept>

#include "common/Xxh64.h"
#include "formats/ReadWithZeroedField.h"

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
  char header[kUuidOffset + kUuidLength];
  in.read(header, std::streamsize(sizeof header));
  if (std::size_t(in.gcount()) != sizeof header || !looksLikeUuid(header + kUuidOffset))
    throw std::runtime_error(fmt::format("{}: the written file has no UUID where OpenVDB writes one", path));

  // Two XXH64 hashes with different seeds: 128 bits, of which the UUID keeps 122.
  Xxh64 first(1), second(2);
  readWithZeroedField(in, kUuidOffset, kUuidLength, [&](const char* bytes, std::size_t count) {
    first.add(bytes, count);
    second.add(bytes, count);
  });
  in.close();

  std::string hex = fmt::format("{:016x}{:016x}", first.value(), second.value());
  hex[12] = '8';                                           // version 8: custom
  hex[16] = "89ab"[(second.value() >> 62) & 3];            // variant 10xx
  const std::string uuid = fmt::format("{}-{}-{}-{}-{}", hex.substr(0, 8), hex.substr(8, 4), hex.substr(12, 4),
                                       hex.substr(16, 4), hex.substr(20, 12));
  std::fstream out(path, std::ios::binary | std::ios::in | std::ios::out);
  out.seekp(std::streamoff(kUuidOffset));
  out.write(uuid.data(), std::streamsize(kUuidLength));
  out.close();
  if (!out) throw std::runtime_error(fmt::format("{}: cannot write the file's UUID", path));
}

}  // namespace baker
