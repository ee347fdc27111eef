#include "volume/AdaptiveVolume.h"

namespace baker {

LevelChoice finestLevelAt(const std::vector<Volume>& levels, int levelCount, const Eigen::Vector3d& world) {
  for (int level = levelCount - 1; level > 0; level -= 1) {
    ProbeInterpolation interpolation = interpolationAt(levels[std::size_t(level)], world);
    if (interpolation.complete()) return {level, interpolation};
  }
  return {0, interpolationAt(levels.front(), world)};
}

void sampleLevels(const std::vector<Volume>& levels, int levelCount, const Eigen::Vector3d& world, float* coefficients,
                  float* visibility, float* skyDirect, float* skyBounced) {
  const LevelChoice choice = finestLevelAt(levels, levelCount, world);
  choice.interpolation.apply(levels[std::size_t(choice.level)], !choice.interpolation.complete(), coefficients, visibility,
                             skyDirect, skyBounced);
}

}  // namespace baker
