#pragma once
#include <string>
#include <vector>

#include "bake/Basis.h"

namespace baker {

// How a basis's coefficients are split into named grids (or channels), the same for every
// file format. When R, G and B share their functions, function i of all three channels is one
// RGB vector grid "rgb_NN"; otherwise each channel's function i is a scalar grid named after
// the channel, e.g. "Y_NN", "Co_NN".
struct CoefficientGrid {
  std::string name;
  bool isVector = false;  // three channels (0, 1, 2) of one function
  int channel = 0;        // for scalar grids
  int function = 0;       // index within the channel's function set
};

std::vector<CoefficientGrid> coefficientGrids(const Basis& basis);

// Sky visibility, function i of channel 0's set: a scalar grid "visibility_NN".
std::string visibilityGridName(int function);
// Probe validity (0 inside geometry and filled from neighbours, 1 valid, 2 moved out of
// geometry) and the world-space offset of each probe from its grid position.
inline constexpr const char* kProbeStateGrid = "probe_state";
inline constexpr const char* kProbeOffsetGrid = "probe_offset";

}  // namespace baker
