#pragma once
#include <cstdint>

namespace baker {

// IEEE 754 binary16 bits of a float, rounded to nearest even (Imath's half); what WebGL's
// HALF_FLOAT textures hold. Values beyond ±65504 become infinities: callers clamp first.
std::uint16_t halfBits(float value);

// The largest finite half.
constexpr float kHalfMax = 65504.0f;

}  // namespace baker
