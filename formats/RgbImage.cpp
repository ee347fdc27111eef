#include "formats/RgbImage.h"

#include <OpenImageIO/imageio.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>

#include "common/Error.h"

namespace baker {
namespace {

void write(const std::string& format, const OIIO::ImageSpec& spec, const void* data, const std::string& path) {
  auto out = OIIO::ImageOutput::create(format);
  if (!out) throw InputError(fmt::format("{}: cannot create a {} writer: {}", path, format, oneLine(OIIO::geterror())));
  if (!out->open(path, spec) || !out->write_image(spec.format, data) || !out->close())
    throw InputError(fmt::format("{}: cannot write: {}", path, oneLine(out->geterror())));
}

std::uint8_t srgbByte(double linear) {
  const double v = std::clamp(linear, 0.0, 1.0);
  const double encoded = v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055;
  return std::uint8_t(std::lround(255.0 * encoded));
}

}  // namespace

RgbImage readRgbImage(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw InputError(fmt::format("{}: no such file", path));
  auto in = OIIO::ImageInput::open(path);
  if (!in) throw InputError(fmt::format("{}: cannot read the image: {}", path, oneLine(OIIO::geterror())));
  const OIIO::ImageSpec& spec = in->spec();
  const int channels = spec.nchannels;
  if (channels != 1 && channels < 3)
    throw InputError(fmt::format("{}: expected RGB or grey, found {} channels", path, channels));
  if (spec.width <= 0 || spec.height <= 0 || spec.depth != 1)
    throw InputError(fmt::format("{}: not a 2D image ({} × {} × {})", path, spec.width, spec.height, spec.depth));
  // The header alone decides the allocation: a few bytes can claim 100000² texels. 16k × 8k
  // is beyond any environment map or light probe in use.
  constexpr double kMaxTexels = 16384.0 * 8192.0;
  if (double(spec.width) * spec.height > kMaxTexels)
    throw InputError(fmt::format("{}: {} × {} texels exceed the limit of 16384 × 8192", path, spec.width, spec.height));
  std::vector<float> source(std::size_t(spec.width) * spec.height * std::min(channels, 3));
  if (!in->read_image(0, 0, 0, std::min(channels, 3), OIIO::TypeDesc::FLOAT, source.data()))
    throw InputError(fmt::format("{}: cannot read the image: {}", path, oneLine(in->geterror())));
  if (channels >= 3) {
    RgbImage image;
    image.width = spec.width;
    image.height = spec.height;
    image.pixels = std::move(source);
    return image;
  }
  RgbImage image(spec.width, spec.height);
  for (std::size_t k = 0; k < source.size(); ++k) std::fill_n(&image.pixels[3 * k], 3, source[k]);
  return image;
}

void writeExr(const RgbImage& image, const std::string& path) {
  write("openexr", OIIO::ImageSpec(image.width, image.height, 3, OIIO::TypeDesc::FLOAT), image.pixels.data(), path);
}

void writeSrgbPng(const RgbImage& image, double exposure, const std::string& path) {
  std::vector<std::uint8_t> bytes(image.pixels.size());
  for (std::size_t k = 0; k < bytes.size(); ++k) bytes[k] = srgbByte(exposure * image.pixels[k]);
  write("png", OIIO::ImageSpec(image.width, image.height, 3, OIIO::TypeDesc::UINT8), bytes.data(), path);
}

}  // namespace baker
