#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace baker {

// What writing a volume in an engine's own format did to the values: how the bake's basis
// became the engine's representation, and how many stored numbers had to be clamped into the
// engine's texel format (counted, so that a user sees it rather than finds it).
struct EngineExport {
  std::string engine;      // "bevy", "threejs"
  std::string conversion;  // one sentence, for the plan and the summary
  std::int64_t clampedValues = 0;
  std::string clampedBecause;  // why values were clamped, when any were
  std::vector<std::string> warnings;  // what the engine may refuse to load (texture limits)
};

// The largest 3D texture side Bevy (wgpu's default limits) and most WebGL 2 implementations take;
// WebGL 2 promises only 256.
constexpr int kCommon3dTextureLimit = 2048;

}  // namespace baker
