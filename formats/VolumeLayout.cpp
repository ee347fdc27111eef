#include "formats/VolumeLayout.h"

#include <fmt/format.h>

namespace baker {

std::vector<CoefficientGrid> coefficientGrids(const Basis& basis) {
  std::vector<CoefficientGrid> grids;
  if (basis.channelsShareFunctions()) {
    for (int f = 0; f < basis.coefficientCount(0); ++f)
      grids.push_back({fmt::format("rgb_{:02}", f), true, 0, f});
    return grids;
  }
  for (int c = 0; c < 3; ++c)
    for (int f = 0; f < basis.coefficientCount(c); ++f)
      grids.push_back({fmt::format("{}_{:02}", channelName(basis.colorSpace(), c), f), false, c, f});
  return grids;
}

std::string visibilityGridName(int function) { return fmt::format("visibility_{:02}", function); }

}  // namespace baker
