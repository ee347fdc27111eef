#pragma once
#include <cstdint>

namespace baker {

// The random numbers of one path, derived only from (seed, probe, ray): a bake draws the same
// numbers for a path whichever thread traces it, so volumes are bit-identical at any thread
// count. A splitmix64 stream: each draw advances a counter and scrambles it.
class PathRandom {
 public:
  PathRandom(std::uint64_t seed, std::uint64_t probe, std::uint64_t ray)
      : state_(scramble(probeKey(seed, probe) ^ ray)) {}
  // The part of the state that (seed, probe) alone decide: worked out once for a probe's paths,
  // it saves each path two of its three scrambles. fromProbeKey(probeKey(s, p), r) is
  // PathRandom(s, p, r).
  static std::uint64_t probeKey(std::uint64_t seed, std::uint64_t probe) { return scramble(scramble(seed) ^ probe); }
  static PathRandom fromProbeKey(std::uint64_t key, std::uint64_t ray) { return PathRandom(scramble(key ^ ray)); }

  // Uniform in [0, 1), 24 bits: exactly representable in float, never 1.
  float uniform() { return float(next() >> 40) * (1.0f / 16777216.0f); }

  // Two such numbers from one draw, its top 24 bits and the 24 below them (every bit of a
  // scrambled draw is well mixed): a path vertex's draws took a fifth of its shading.
  void uniformPair(float* first, float* second) {
    const std::uint64_t bits = next();
    *first = float(bits >> 40) * (1.0f / 16777216.0f);
    *second = float((bits >> 16) & 0xffffffu) * (1.0f / 16777216.0f);
  }

  static std::uint64_t scramble(std::uint64_t h) {
    h += 0x9e3779b97f4a7c15ull;
    h = (h ^ (h >> 30)) * 0xbf58476d1ce4e5b9ull;
    h = (h ^ (h >> 27)) * 0x94d049bb133111ebull;
    return h ^ (h >> 31);
  }

 private:
  explicit PathRandom(std::uint64_t state) : state_(state) {}
  std::uint64_t next() { return scramble(state_ += 0x632be59bd9b4e019ull); }

  std::uint64_t state_;
};

}  // namespace baker
