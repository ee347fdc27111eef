#pragma once

namespace baker {

// The power heuristic's share (Veach) of a technique of density a against one of density b,
// each density already times its number of samples.
// In double, so that the squares of densities of bright, tiny sources do not overflow.
inline float powerHeuristic(float a, float b) {
  const double a2 = double(a) * double(a), b2 = double(b) * double(b);
  return a2 + b2 > 0.0 ? float(a2 / (a2 + b2)) : 0.0f;
}

}  // namespace baker
