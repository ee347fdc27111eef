#pragma once
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

namespace baker {

// A float's spacing to the next larger one, for positive finite normal values: nextafter
// without the library call.
inline float floatStep(float magnitude) {
  std::uint32_t bits;
  std::memcpy(&bits, &magnitude, sizeof bits);
  const std::uint32_t exponent = bits & 0x7f800000u;
  if (exponent <= (23u << 23)) return std::nextafter(magnitude, std::numeric_limits<float>::infinity()) - magnitude;
  const std::uint32_t stepBits = exponent - (23u << 23);
  float step;
  std::memcpy(&step, &stepBits, sizeof step);
  return step;
}

// How far a ray starts off the surface it leaves. A hit point is only known to a few units in
// the last place of its largest coordinate (and of the scene's size, for points near the
// origin): step 32 of those off the surface, so that the same scene at any scale or place bakes
// the same.
inline float surfaceRayOffset(const Eigen::Vector3f& point, float sceneScale) {
  return 32.0f * floatStep(std::max(point.cwiseAbs().maxCoeff(), sceneScale));
}

}  // namespace baker
