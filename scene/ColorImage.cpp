#include "scene/ColorImage.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <stdexcept>

namespace baker {
namespace {

const std::array<float, 256>& srgbTable() {
  static const std::array<float, 256> table = [] {
    std::array<float, 256> t{};
    for (int i = 0; i < 256; ++i) t[i] = srgbToLinear(float(i) / 255.0f);
    return t;
  }();
  return table;
}

// std::floor without the library call (this build targets baseline x86-64, which has no
// rounding instruction); exact wherever a double still has a fractional part.
double floorOf(double t) {
  if (!(std::abs(t) < 4503599627370496.0)) return std::floor(t);  // 2^52: already whole (or NaN)
  const double whole = double(std::int64_t(t));
  return whole > t ? whole - 1.0 : whole;
}

// Brings a texture coordinate into one period (or onto the edge for clamping) before it is
// scaled to texels, so that huge or negative coordinates cannot overflow a texel index.
double reduce(double t, Wrap wrap) {
  switch (wrap) {
    case Wrap::Repeat: return t - floorOf(t);
    case Wrap::MirroredRepeat: return t - 2.0 * floorOf(t / 2.0);
    case Wrap::ClampToEdge: break;
  }
  return std::clamp(t, 0.0, 1.0);
}

// The texel a (possibly out-of-range) index reads under `wrap`; the reduced coordinate keeps
// the index within one neighbour of a single (mirrored: double) period.
int wrapIndex(int i, int n, Wrap wrap) {
  // One step of a period instead of a remainder: an integer division costs more than the rest
  // of a texture lookup.
  switch (wrap) {
    case Wrap::Repeat: {
      const int m = i < 0 ? i + n : i >= n ? i - n : i;
      return m >= 0 && m < n ? m : ((i % n) + n) % n;
    }
    case Wrap::MirroredRepeat: {
      int m = i < 0 ? i + 2 * n : i >= 2 * n ? i - 2 * n : i;
      if (m < 0 || m >= 2 * n) m = ((i % (2 * n)) + 2 * n) % (2 * n);
      return m < n ? m : 2 * n - 1 - m;
    }
    case Wrap::ClampToEdge: break;
  }
  return std::clamp(i, 0, n - 1);
}

}  // namespace

float srgbToLinear(float encoded) {
  return encoded <= 0.04045f ? encoded / 12.92f : std::pow((encoded + 0.055f) / 1.055f, 2.4f);
}

ColorImage ColorImage::fromBytes(int width, int height, std::vector<std::uint8_t> rgba) {
  if (width <= 0 || height <= 0 || rgba.size() != std::size_t(width) * height * 4)
    throw std::invalid_argument("ColorImage: pixel data does not match the image size");
  ColorImage image;
  image.width_ = width;
  image.height_ = height;
  image.bytes_.assign(rgba.begin(), rgba.end());  // copied once into storage that can take huge pages
  return image;
}

ColorImage ColorImage::fromLinear(int width, int height, std::vector<float> rgba) {
  if (width <= 0 || height <= 0 || rgba.size() != std::size_t(width) * height * 4)
    throw std::invalid_argument("ColorImage: pixel data does not match the image size");
  ColorImage image;
  image.width_ = width;
  image.height_ = height;
  image.linear_.assign(rgba.begin(), rgba.end());  // likewise
  return image;
}

Eigen::Vector4f ColorImage::texel(int x, int y) const {
  const std::size_t k = (std::size_t(y) * width_ + x) * 4;
  if (!bytes_.empty()) {
    const std::array<float, 256>& srgb = srgbTable();
    return {srgb[bytes_[k]], srgb[bytes_[k + 1]], srgb[bytes_[k + 2]], float(bytes_[k + 3]) / 255.0f};
  }
  return {linear_[k], linear_[k + 1], linear_[k + 2], linear_[k + 3]};
}

ColorImage::Footprint ColorImage::footprint(const Eigen::Vector2f& uv, const SamplerState& sampler) const {
  const double s = reduce(std::isfinite(uv.x()) ? uv.x() : 0.0, sampler.wrapS) * width_;
  const double t = reduce(std::isfinite(uv.y()) ? uv.y() : 0.0, sampler.wrapT) * height_;
  Footprint f;
  f.nearest = sampler.nearest;
  if (sampler.nearest) {
    f.x0 = f.x1 = wrapIndex(int(floorOf(s)), width_, sampler.wrapS);
    f.y0 = f.y1 = wrapIndex(int(floorOf(t)), height_, sampler.wrapT);
    return f;
  }
  // Texel centres sit at half-integer positions, so bilinear weights come from s − ½.
  const double px = s - 0.5, py = t - 0.5;
  const double fx0 = floorOf(px), fy0 = floorOf(py);
  f.ax = float(px - fx0);
  f.ay = float(py - fy0);
  f.x0 = wrapIndex(int(fx0), width_, sampler.wrapS);
  f.x1 = wrapIndex(int(fx0) + 1, width_, sampler.wrapS);
  f.y0 = wrapIndex(int(fy0), height_, sampler.wrapT);
  f.y1 = wrapIndex(int(fy0) + 1, height_, sampler.wrapT);
  return f;
}

Eigen::Vector4f ColorImage::sample(const Footprint& f) const {
  if (f.nearest) return texel(f.x0, f.y0);
  return (1.0f - f.ay) * ((1.0f - f.ax) * texel(f.x0, f.y0) + f.ax * texel(f.x1, f.y0)) +
         f.ay * ((1.0f - f.ax) * texel(f.x0, f.y1) + f.ax * texel(f.x1, f.y1));
}

void ColorImage::prefetch(const Footprint& f) const {
  for (int y : {f.y0, f.y1})
    for (int x : {f.x0, f.x1}) {
      const std::size_t k = (std::size_t(y) * width_ + x) * 4;
      if (bytes_.empty()) {
        __builtin_prefetch(linear_.data() + k);
      } else {
        __builtin_prefetch(bytes_.data() + k);
      }
    }
}

}  // namespace baker
