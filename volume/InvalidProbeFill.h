#pragma once
#include <cstdint>
#include <vector>

#include "volume/ProbeGrid.h"
#include "volume/ProbeRows.h"
#include "volume/ProbeState.h"

namespace baker {

// Gives each Invalid probe (states[p]) values from its valid face neighbours, in passes: a pass
// fills every unfilled Invalid probe with a Valid, Relocated or already filled neighbour with
// the mean of those neighbours' values as they stood before the pass, until a pass fills none.
// values holds valuesPerProbe floats per probe in ProbeGrid::linearIndex order; the Invalid
// probes' own values are discarded, and those no valid probe reaches (a grid with none) get
// zeros. Interpolated probes (an adaptive level's border, holding the coarser levels' values)
// feed only the Invalid probes left after that: the fill inside geometry carries the traced light
// of the nearest surface, as in a uniform bake. Serial and order-free, so the result is the same
// on any machine. It reads the whole grid: a bake cut into shards runs it once, when the parts are
// merged.
void fillInvalidProbes(const ProbeGrid& grid, const std::vector<ProbeState>& states, int valuesPerProbe,
                       std::vector<float>& values);
// The same over the probes `rows` holds (states and values by row): a probe not held is neither
// filled nor a neighbour.
void fillInvalidProbes(const ProbeGrid& grid, const ProbeRows& rows, const std::vector<ProbeState>& states,
                       int valuesPerProbe, std::vector<float>& values);

}  // namespace baker
