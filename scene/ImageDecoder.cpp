#include "scene/ImageDecoder.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstring>

#include "common/Error.h"
#include "images/ImageFiles.h"

namespace baker {
namespace {

// The image library picks its reader from a file name's extension, and a glTF image in memory has
// none, so the name is chosen from the signature: glTF core allows exactly PNG and JPEG.
const char* formatName(const std::vector<unsigned char>& bytes) {
  static const unsigned char png[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (bytes.size() >= 8 && std::memcmp(bytes.data(), png, 8) == 0) return "image.png";
  if (bytes.size() >= 3 && bytes[0] == 0xff && bytes[1] == 0xd8 && bytes[2] == 0xff) return "image.jpg";
  return nullptr;
}

// Spreads `channels` decoded channels over RGBA: grey fills RGB, a missing alpha is opaque.
template <typename T>
std::vector<T> expandToRgba(const std::vector<T>& source, std::size_t texels, int channels, T opaque) {
  std::vector<T> rgba(texels * 4);
  for (std::size_t k = 0; k < texels; ++k) {
    const T* in = &source[k * channels];
    T* out = &rgba[k * 4];
    if (channels <= 2) {
      out[0] = out[1] = out[2] = in[0];
      out[3] = channels == 2 ? in[1] : opaque;
    } else {
      out[0] = in[0];
      out[1] = in[1];
      out[2] = in[2];
      out[3] = channels == 4 ? in[3] : opaque;
    }
  }
  return rgba;
}

}  // namespace

ColorImage decodeColorImage(const std::vector<unsigned char>& encoded, const std::string& what) {
  const char* name = formatName(encoded);
  if (!name) throw InputError(fmt::format("{}: not a PNG or JPEG image", what));
  ImageReader in(encoded.data(), encoded.size(), name, what);
  const ImageHeader& spec = in.header();
  if (spec.width <= 0 || spec.height <= 0 || spec.depth != 1)
    throw InputError(fmt::format("{}: not a 2D image ({} × {} × {})", what, spec.width, spec.height, spec.depth));
  const long long texels = (long long)spec.width * spec.height;
  if (texels > kMaxTextureTexels)
    throw InputError(fmt::format("{}: {} × {} texels exceed the limit of {}", what, spec.width, spec.height,
                                 kMaxTextureTexels));
  const int channels = std::min(spec.channels, 4);
  if (spec.storage == PixelType::Byte) {
    std::vector<std::uint8_t> source(std::size_t(texels) * channels);
    if (!in.readBytes(channels, source.data())) throw InputError(fmt::format("{}: cannot decode: {}", what, in.error()));
    return ColorImage::fromBytes(spec.width, spec.height, expandToRgba<std::uint8_t>(source, texels, channels, 255));
  }
  // 16-bit PNGs: normalised values, still sRGB-encoded in RGB.
  std::vector<float> source(std::size_t(texels) * channels);
  if (!in.readFloats(channels, source.data())) throw InputError(fmt::format("{}: cannot decode: {}", what, in.error()));
  std::vector<float> rgba = expandToRgba<float>(source, texels, channels, 1.0f);
  for (std::size_t k = 0; k < rgba.size(); ++k)
    if (k % 4 != 3) rgba[k] = srgbToLinear(std::clamp(rgba[k], 0.0f, 1.0f));
  return ColorImage::fromLinear(spec.width, spec.height, std::move(rgba));
}

}  // namespace baker
