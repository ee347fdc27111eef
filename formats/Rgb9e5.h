#pragma once
#include <Eigen/Core>
#include <cstdint>

namespace baker {

// The shared-exponent texel of VK_FORMAT_E5B9G9R9_UFLOAT_PACK32 (EXT_texture_shared_exponent):
// three 9-bit mantissas with one 5-bit exponent, bias 15, no implicit leading one; a channel
// holds 0 … 65408 to about 1/512 of the texel's largest channel.
constexpr float kRgb9e5Max = 65408.0f;

struct Rgb9e5Packing {
  std::uint32_t bits = 0;
  int clamped = 0;  // channels outside [0, kRgb9e5Max] (or NaN) that had to be moved into it
};

Rgb9e5Packing packRgb9e5(const Eigen::Vector3f& rgb);
Eigen::Vector3f unpackRgb9e5(std::uint32_t bits);

}  // namespace baker
