#include "images/RgbImage.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>

#include "common/Error.h"
#include "images/ImageFiles.h"

namespace baker {
namespace {

void writeRgb(const std::string& format, const RgbImage& image, PixelType type, const void* pixels,
              const std::string& path) {
  ImageToWrite out;
  out.format = format;
  out.width = image.width;
  out.height = image.height;
  out.channelNames = {"R", "G", "B"};
  out.pixelType = type;
  out.pixels = pixels;
  std::string error;
  if (!writeImage(out, path, &error)) throw InputError(fmt::format("{}: cannot write: {}", path, error));
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
  ImageReader in(path);
  const ImageHeader& spec = in.header();
  const int channels = spec.channels;
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
  if (!in.readFloats(std::min(channels, 3), source.data()))
    throw InputError(fmt::format("{}: cannot read the image: {}", path, in.error()));
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
  writeRgb("openexr", image, PixelType::Float, image.pixels.data(), path);
}

void writeSrgbPng(const RgbImage& image, double exposure, const std::string& path) {
  std::vector<std::uint8_t> bytes(image.pixels.size());
  for (std::size_t k = 0; k < bytes.size(); ++k) bytes[k] = srgbByte(exposure * image.pixels[k]);
  writeRgb("png", image, PixelType::Byte, bytes.data(), path);
}

}  // namespace baker
