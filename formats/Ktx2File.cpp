#include "formats/Ktx2File.h"

#include <fmt/format.h>

#include <algorithm>

#include "common/Error.h"

namespace baker {
namespace {

constexpr std::uint8_t kIdentifier[12] = {0xAB, 0x4B, 0x54, 0x58, 0x20, 0x32, 0x30, 0xBB, 0x0D, 0x0A, 0x1A, 0x0A};
constexpr std::size_t kHeaderBytes = 80;
constexpr std::size_t kLevelEntryBytes = 24;

std::size_t alignedTo4(std::size_t n) { return (n + 3) & ~std::size_t(3); }

class ByteWriter {
 public:
  void u32(std::uint32_t v) { little(v, 4); }
  void u64(std::uint64_t v) { little(v, 8); }
  void append(const void* data, std::size_t n) {
    const auto* p = static_cast<const std::uint8_t*>(data);
    bytes.insert(bytes.end(), p, p + n);
  }
  void padTo4() { bytes.resize(alignedTo4(bytes.size()), 0); }
  std::vector<std::uint8_t> bytes;

 private:
  void little(std::uint64_t v, int n) {
    for (int i = 0; i < n; ++i) bytes.push_back(std::uint8_t(v >> (8 * i)));
  }
};

std::vector<std::uint8_t> keyValueData(const std::vector<std::pair<std::string, std::string>>& entries) {
  ByteWriter kvd;
  for (const auto& [key, value] : entries) {
    kvd.u32(std::uint32_t(key.size() + 1 + value.size() + 1));
    kvd.append(key.c_str(), key.size() + 1);
    kvd.append(value.c_str(), value.size() + 1);
    kvd.padTo4();
  }
  return kvd.bytes;
}

// Reads little-endian fields of a file whose size was checked before each read.
class ByteReader {
 public:
  ByteReader(const std::vector<std::uint8_t>& bytes, const std::string& path) : bytes_(bytes), path_(path) {}
  std::uint64_t at(std::size_t offset, int n, const char* field) const {
    if (offset + n > bytes_.size())
      throw InputError(fmt::format("{}: KTX2 {} lies beyond the file's {} bytes", path_, field, bytes_.size()));
    std::uint64_t v = 0;
    for (int i = n - 1; i >= 0; --i) v = (v << 8) | bytes_[offset + i];
    return v;
  }
  // A [offset, offset + length) range that must lie inside the file.
  void requireRange(std::uint64_t offset, std::uint64_t length, const char* field) const {
    if (offset > bytes_.size() || length > bytes_.size() - offset)
      throw InputError(fmt::format("{}: KTX2 {} (offset {}, {} bytes) lies beyond the file's {} bytes", path_, field,
                                   offset, length, bytes_.size()));
  }

 private:
  const std::vector<std::uint8_t>& bytes_;
  const std::string& path_;
};

}  // namespace

std::vector<std::uint32_t> rgb9e5DataFormatDescriptor() {
  // Words: totalSize; vendor 0 and descriptor type 0; version 2 and block size 24 + 16·6;
  // colour model RGBSDA, primaries BT.709, linear transfer, straight alpha; a 1×1×1 block;
  // 4 bytes in plane 0. Then per channel R, G, B: the 9-bit mantissa (upper 8448 = 1.0 as
  // mantissa 256 with exponent 16), and the shared 5-bit exponent at bit 27 (the exponent
  // qualifier 0x20; lower 15 = the bias, upper 31).
  std::vector<std::uint32_t> words = {124, 0, 2u | (120u << 16), 1u | (1u << 8) | (1u << 16), 0, 4, 0};
  for (std::uint32_t channel = 0; channel < 3; ++channel) {
    const std::uint32_t mantissa[4] = {(9 * channel) | (8u << 16) | (channel << 24), 0, 0, 8448};
    const std::uint32_t exponent[4] = {27u | (4u << 16) | ((channel | 0x20u) << 24), 0, 15, 31};
    words.insert(words.end(), mantissa, mantissa + 4);
    words.insert(words.end(), exponent, exponent + 4);
  }
  return words;
}

std::vector<std::uint8_t> encodeKtx2(const Ktx2Texture3D& t) {
  const std::size_t dfdOffset = kHeaderBytes + kLevelEntryBytes;
  const std::size_t dfdBytes = t.dataFormatDescriptor.size() * 4;
  const std::vector<std::uint8_t> kvd = keyValueData(t.keyValues);
  const std::size_t kvdOffset = kvd.empty() ? 0 : dfdOffset + dfdBytes;
  // Level data is aligned to lcm(texel block size, 4): 4 for every format written here.
  const std::size_t levelOffset = alignedTo4(dfdOffset + dfdBytes + kvd.size());

  ByteWriter w;
  w.append(kIdentifier, sizeof kIdentifier);
  for (std::uint32_t v : {t.vkFormat, t.typeSize, t.width, t.height, t.depth, 0u /*layers*/, 1u /*faces*/,
                          1u /*levels*/, 0u /*supercompression*/})
    w.u32(v);
  w.u32(std::uint32_t(dfdOffset));
  w.u32(std::uint32_t(dfdBytes));
  w.u32(std::uint32_t(kvdOffset));
  w.u32(std::uint32_t(kvd.size()));
  w.u64(0);  // no supercompression global data
  w.u64(0);
  w.u64(levelOffset);
  w.u64(t.texels.size());
  w.u64(t.texels.size());
  for (std::uint32_t word : t.dataFormatDescriptor) w.u32(word);
  w.append(kvd.data(), kvd.size());
  w.bytes.resize(levelOffset, 0);
  w.append(t.texels.data(), t.texels.size());
  return w.bytes;
}

Ktx2Texture3D decodeKtx2(const std::vector<std::uint8_t>& bytes, const std::string& path) {
  if (bytes.size() < kHeaderBytes + kLevelEntryBytes || !std::equal(kIdentifier, kIdentifier + 12, bytes.begin()))
    throw InputError(fmt::format("{}: not a KTX 2.0 file (its identifier is missing)", path));
  const ByteReader r(bytes, path);
  Ktx2Texture3D t;
  t.vkFormat = std::uint32_t(r.at(12, 4, "vkFormat"));
  t.typeSize = std::uint32_t(r.at(16, 4, "typeSize"));
  t.width = std::uint32_t(r.at(20, 4, "pixelWidth"));
  t.height = std::uint32_t(r.at(24, 4, "pixelHeight"));
  t.depth = std::uint32_t(r.at(28, 4, "pixelDepth"));
  if (r.at(32, 4, "layerCount") > 1 || r.at(36, 4, "faceCount") != 1 || r.at(40, 4, "levelCount") != 1)
    throw InputError(fmt::format("{}: a KTX2 array, cube map or mip chain; expected one 3D texture of one level", path));
  if (r.at(44, 4, "supercompressionScheme") != 0)
    throw InputError(fmt::format("{}: KTX2 supercompressionScheme {} (only uncompressed data is read)", path,
                                 r.at(44, 4, "supercompressionScheme")));
  if (t.width == 0 || t.height == 0 || t.depth == 0)
    throw InputError(fmt::format("{}: KTX2 pixelWidth, pixelHeight and pixelDepth must be positive for a 3D texture", path));
  const std::uint64_t dfdOffset = r.at(48, 4, "dfdByteOffset"), dfdBytes = r.at(52, 4, "dfdByteLength");
  const std::uint64_t kvdOffset = r.at(56, 4, "kvdByteOffset"), kvdBytes = r.at(60, 4, "kvdByteLength");
  const std::uint64_t levelOffset = r.at(80, 8, "level 0 byteOffset"), levelBytes = r.at(88, 8, "level 0 byteLength");
  r.requireRange(dfdOffset, dfdBytes, "data format descriptor");
  r.requireRange(kvdOffset, kvdBytes, "key/value data");
  r.requireRange(levelOffset, levelBytes, "level 0");
  if (dfdBytes % 4 != 0 || dfdBytes < 4 || r.at(dfdOffset, 4, "dfdTotalSize") != dfdBytes)
    throw InputError(fmt::format("{}: KTX2 dfdByteLength {} does not match the descriptor's dfdTotalSize", path, dfdBytes));
  for (std::uint64_t i = 0; i < dfdBytes; i += 4) t.dataFormatDescriptor.push_back(std::uint32_t(r.at(dfdOffset + i, 4, "DFD")));
  for (std::uint64_t at = kvdOffset; at + 4 <= kvdOffset + kvdBytes;) {
    const std::uint64_t length = r.at(at, 4, "keyAndValueByteLength");
    r.requireRange(at + 4, length, "key/value entry");
    if (at + 4 + length > kvdOffset + kvdBytes)
      throw InputError(fmt::format("{}: a KTX2 key/value entry runs past kvdByteLength", path));
    const std::string entry(bytes.begin() + std::ptrdiff_t(at + 4), bytes.begin() + std::ptrdiff_t(at + 4 + length));
    const std::size_t nul = entry.find('\0');
    if (nul != std::string::npos) {
      std::string value = entry.substr(nul + 1);
      if (!value.empty() && value.back() == '\0') value.pop_back();
      t.keyValues.push_back({entry.substr(0, nul), value});
    }
    at = alignedTo4(at + 4 + length);
  }
  t.texels.assign(bytes.begin() + std::ptrdiff_t(levelOffset), bytes.begin() + std::ptrdiff_t(levelOffset + levelBytes));
  return t;
}

}  // namespace baker
