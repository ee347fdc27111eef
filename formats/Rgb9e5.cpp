#include "formats/Rgb9e5.h"

#include <algorithm>
#include <cmath>

namespace baker {
namespace {

constexpr int kMantissaBits = 9;
constexpr int kExponentBias = 15;

}  // namespace

// The encoding of the extension's specification: the exponent from the largest channel, raised
// by one when rounding that channel's mantissa would overflow 9 bits.
Rgb9e5Packing packRgb9e5(const Eigen::Vector3f& rgb) {
  Rgb9e5Packing packing;
  double c[3];
  for (int i = 0; i < 3; ++i) {
    const double v = rgb[i];
    c[i] = std::isnan(v) ? 0.0 : std::clamp(v, 0.0, double(kRgb9e5Max));
    if (!(c[i] == v)) ++packing.clamped;
  }
  const double largest = std::max({c[0], c[1], c[2]});
  int exponent = largest > 0.0 ? std::max(-kExponentBias - 1, int(std::floor(std::log2(largest)))) + 1 + kExponentBias
                               : 0;
  if (std::floor(largest / std::exp2(exponent - kExponentBias - kMantissaBits) + 0.5) == double(1 << kMantissaBits))
    ++exponent;
  const double step = std::exp2(exponent - kExponentBias - kMantissaBits);
  std::uint32_t bits = std::uint32_t(exponent) << 27;
  for (int i = 0; i < 3; ++i) bits |= std::uint32_t(std::floor(c[i] / step + 0.5)) << (kMantissaBits * i);
  packing.bits = bits;
  return packing;
}

Eigen::Vector3f unpackRgb9e5(std::uint32_t bits) {
  const double step = std::exp2(int(bits >> 27) - kExponentBias - kMantissaBits);
  Eigen::Vector3f rgb;
  for (int i = 0; i < 3; ++i) rgb[i] = float(double((bits >> (kMantissaBits * i)) & 0x1ffu) * step);
  return rgb;
}

}  // namespace baker
