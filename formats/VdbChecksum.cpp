#include "formats/VdbChecksum.h"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <optional>
#include <stdexcept>
#include <vector>

#include "common/Error.h"
#include "common/Fnv1a64.h"
#include "common/Xxh64.h"
#include "formats/ReadWithZeroedField.h"

namespace baker {
namespace {

constexpr std::size_t kDigits = 16;

void appendLength(std::string& bytes, std::uint32_t length) {
  // OpenVDB writes lengths as 32-bit integers in the machine's byte order: little-endian here.
  for (int b = 0; b < 4; ++b) bytes.push_back(char((length >> (8 * b)) & 0xff));
}

// How OpenVDB serialises one string metadata entry under `key`, up to its value: the name, the
// type name and the value's size, each length-prefixed.
std::string entryPrefix(const std::string& key) {
  std::string bytes;
  const std::string type = "string";
  appendLength(bytes, std::uint32_t(key.size()));
  bytes += key;
  appendLength(bytes, std::uint32_t(type.size()));
  bytes += type;
  appendLength(bytes, std::uint32_t(kDigits));
  return bytes;
}

// Offsets of the digits of the entry under `key` (just after each occurrence of its prefix) in the
// first `limit` bytes, read in pieces that overlap by the prefix's length so that no occurrence is
// split; at most two are listed.
std::vector<std::uint64_t> digitOffsets(std::ifstream& in, const std::string& key, std::uint64_t limit) {
  const std::string prefix = entryPrefix(key);
  std::vector<std::uint64_t> offsets;
  std::vector<char> window(1 << 16);
  std::size_t kept = 0;
  std::uint64_t windowStart = 0;
  in.clear();
  in.seekg(0);
  while (in && windowStart + kept < limit) {
    const std::uint64_t wanted = std::min<std::uint64_t>(window.size() - kept, limit - windowStart - kept);
    in.read(window.data() + kept, std::streamsize(wanted));
    const std::size_t filled = kept + std::size_t(in.gcount());
    for (auto it = window.begin(); it != window.begin() + std::ptrdiff_t(filled);) {
      it = std::search(it, window.begin() + std::ptrdiff_t(filled), prefix.begin(), prefix.end());
      if (it == window.begin() + std::ptrdiff_t(filled)) break;
      const std::uint64_t at = windowStart + std::uint64_t(it - window.begin());
      offsets.push_back(at + prefix.size());
      if (offsets.size() > 1) return offsets;
      ++it;
    }
    if (filled == kept) break;
    kept = std::min(filled, prefix.size() - 1);
    std::memmove(window.data(), window.data() + filled - kept, kept);
    windowStart += filled - kept;
  }
  return offsets;
}

// The hash `Hash` of the file's bytes with the kDigits bytes at `digits` read as '0'.
template <typename Hash>
std::uint64_t hashWithPlaceholder(std::ifstream& in, std::uint64_t digits) {
  Hash hash;
  readWithZeroedField(in, digits, kDigits, [&](const char* bytes, std::size_t count) { hash.add(bytes, count); });
  return hash.value();
}

// The stored digits as a number; nullopt unless they are 16 lower-case hex digits.
std::optional<std::uint64_t> readDigits(std::ifstream& in, std::uint64_t digits) {
  in.clear();
  in.seekg(std::streamoff(digits));
  char text[kDigits];
  in.read(text, std::streamsize(kDigits));
  if (std::size_t(in.gcount()) != kDigits) return std::nullopt;
  for (char c : text)
    if (!((c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'))) return std::nullopt;
  std::uint64_t value = 0;
  std::from_chars(text, text + kDigits, value, 16);
  return value;
}

}  // namespace

void sealVdbChecksum(const std::string& path, std::uint64_t headerBytes) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(fmt::format("{}: cannot reopen the written file to seal it", path));
  const std::vector<std::uint64_t> offsets = digitOffsets(in, kVdbChecksumKey, headerBytes);
  if (offsets.size() != 1 || readDigits(in, offsets[0]) != std::uint64_t(0))
    throw std::runtime_error(fmt::format("{}: the checksum placeholder is not in the written file's metadata exactly once", path));
  const std::string digits = fmt::format("{:016x}", hashWithPlaceholder<Xxh64>(in, offsets[0]));
  in.close();
  std::fstream out(path, std::ios::binary | std::ios::in | std::ios::out);
  out.seekp(std::streamoff(offsets[0]));
  out.write(digits.data(), std::streamsize(kDigits));
  out.close();
  if (!out) throw std::runtime_error(fmt::format("{}: cannot write the checksum", path));
}

void requireVdbChecksum(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(fmt::format("{}: cannot read the file", path));
  constexpr std::uint64_t kWholeFile = ~std::uint64_t(0);
  std::string key = kVdbChecksumKey;
  std::vector<std::uint64_t> offsets = digitOffsets(in, key, kWholeFile);
  if (offsets.empty()) {
    key = kVdbLegacyChecksumKey;
    offsets = digitOffsets(in, key, kWholeFile);
  }
  if (offsets.empty())
    throw InputError(fmt::format("{}: not a readable OpenVDB volume: it has no '{}' metadata (not written by "
                                 "baker, or by a version before volume format 3: bake it again)",
                                 path, kVdbChecksumKey));
  if (offsets.size() > 1)
    throw InputError(fmt::format("{}: not a readable OpenVDB volume: '{}' appears more than once", path, key));
  // Compared as numbers, never as text: a fuzzer that sees the text it is compared with learns
  // to write it into the file (libFuzzer does this with memcmp arguments).
  const std::optional<std::uint64_t> stored = readDigits(in, offsets[0]);
  const std::uint64_t actual = key == kVdbChecksumKey ? hashWithPlaceholder<Xxh64>(in, offsets[0])
                                                      : hashWithPlaceholder<Fnv1a64>(in, offsets[0]);
  if (stored != actual)
    throw InputError(fmt::format("{}: not a readable OpenVDB volume: its bytes do not match its checksum ({} "
                                 "stored, {:016x} computed): the file is corrupted, truncated or was edited",
                                 path, stored ? fmt::format("{:016x}", *stored) : "none", actual));
}

}  // namespace baker
