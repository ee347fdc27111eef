#pragma once

namespace baker {

// The power heuristic's share (Veach) of a technique of density a against one of density b,
// each density already times its number of samples.
inline float powerHeuristic(float a, float b) {
  const float a2 = a * a, b2 = b * b;
  return a2 + b2 > 0.0f ? a2 / (a2 + b2) : 0.0f;
}

}  // namespace baker
