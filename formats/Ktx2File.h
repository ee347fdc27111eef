#pragma once
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace baker {

// A 3D texture of one mip level in a KTX 2.0 file (Khronos KTX File Format Specification 2.0),
// no supercompression: what an engine uploads as it is. Written by this project, since Debian
// has no libktx.
struct Ktx2Texture3D {
  std::uint32_t vkFormat = 0;
  std::uint32_t typeSize = 1;
  std::uint32_t width = 0, height = 0, depth = 0;
  std::vector<std::uint32_t> dataFormatDescriptor;  // every word, dfdTotalSize first
  std::vector<std::pair<std::string, std::string>> keyValues;  // sorted by key, as the spec asks
  std::vector<std::uint8_t> texels;  // x fastest, then y, then z
};

// VK_FORMAT_E5B9G9R9_UFLOAT_PACK32 and its Basic Data Format Descriptor, as the Khronos Data
// Format Specification's example for it describes the format.
constexpr std::uint32_t kVkFormatE5B9G9R9 = 123;
std::vector<std::uint32_t> rgb9e5DataFormatDescriptor();

std::vector<std::uint8_t> encodeKtx2(const Ktx2Texture3D& texture);

// Parses what encodeKtx2 writes (any vkFormat, one level, no supercompression), checking every
// offset and length against the file's size. InputError naming `path` and the field.
Ktx2Texture3D decodeKtx2(const std::vector<std::uint8_t>& bytes, const std::string& path);

}  // namespace baker
