#pragma once
#include <map>
#include <string>
#include <vector>

#include "bake/ProbeGrid.h"

namespace baker {

// A baked irradiance volume: per probe, the basis coefficients of the irradiance E(n) it receives,
// laid out as Basis describes (channel after channel). Probe p = i + nx·(j + ny·k).
struct Volume {
  ProbeGrid grid;
  std::string basisName;
  int coefficientsPerProbe = 0;
  std::vector<float> coefficients;
  // What produced it (rays, scene file, ...): written to the file's metadata as it is.
  std::map<std::string, std::string> settings;

  const float* probe(std::int64_t index) const { return coefficients.data() + index * coefficientsPerProbe; }
};

}  // namespace baker
