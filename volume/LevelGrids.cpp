#include "volume/LevelGrids.h"

#include <cmath>

namespace baker {

std::vector<ProbeGrid> levelGrids(const ProbeGrid& finest, int levels) {
  std::vector<ProbeGrid> grids{finest};
  for (int level = 1; level < levels; ++level) {
    const ProbeGrid& fine = grids.front();
    ProbeGrid coarse;
    coarse.spacing = fine.spacing * kLevelRatio;
    for (int a = 0; a < 3; ++a) {
      // Whole coarse cells over the fine cells, the excess (0 to 2 fine cells) shared out on
      // both sides; each coarse probe is the fine probe at the centre of its cell.
      coarse.dims[a] = (fine.dims[a] + kLevelRatio - 1) / kLevelRatio;
      const int pad = (coarse.dims[a] * kLevelRatio - fine.dims[a]) / 2;
      coarse.origin[a] = fine.origin[a] + fine.spacing * (1 - pad);
    }
    grids.insert(grids.begin(), coarse);
  }
  return grids;
}

bool nestsIn(const ProbeGrid& fine, const ProbeGrid& coarse) {
  const double spacing = coarse.spacing / kLevelRatio;
  if (!(std::abs(fine.spacing - spacing) <= 1e-12 * spacing)) return false;
  for (int a = 0; a < 3; ++a) {
    // Every coarse probe is a fine lattice point: their origins are a whole number of fine
    // spacings apart.
    const double offset = (coarse.origin[a] - fine.origin[a]) / spacing;
    if (!(std::abs(offset - std::round(offset)) <= 1e-6)) return false;
  }
  return true;
}

}  // namespace baker
