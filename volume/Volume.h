#pragma once
#include <Eigen/Core>
#include <array>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "volume/DistanceMoments.h"
#include "volume/ProbeGrid.h"
#include "volume/ProbeRows.h"
#include "volume/ProbeState.h"
#include "volume/Shard.h"
#include "volume/SkyRadiance.h"

namespace baker {

// A baked volume: per probe, the basis coefficients of the irradiance E(n) it receives or of the
// incoming radiance L(ω) (its setting "signal", basis/StoredSignal.h), laid out as Basis
// describes (channel after channel), and of its sky visibility. Probe
// p = i + nx·(j + ny·k) has row rowOf(p) of every per-probe array: row p, unless the volume is a
// shard's part as baked, which holds only its own bricks (ProbeRows).
struct Volume {
  ProbeGrid grid;
  ProbeRows rows;
  std::string basisName;
  int coefficientsPerProbe = 0;
  std::vector<float> coefficients;
  // The part of `coefficients` that is the sky seen directly along the probe's own rays (the
  // rays that escaped, and the sky's direct-view samples), in the same layout: what relighting
  // takes away exactly, and coefficients − skyDirect the light a decoder keeps when it swaps the
  // sky. coefficientsPerProbe values per probe when `keepsSkyDirect`, else none.
  bool keepsSkyDirect = false;
  std::vector<float> skyDirect;
  // The part of `coefficients` that is the sky's light off surfaces (paths that reflected before
  // the sky lit them), in the same layout: what relighting scales to the new sky.
  // coefficientsPerProbe values per probe when `keepsSkyBounced` (bakes that keep skyDirect and
  // whose paths reflect), else none.
  bool keepsSkyBounced = false;
  std::vector<float> skyBounced;
  // Sky visibility in channel 0's functions: V(n) = (1/π) ∫ V(ω) max(0, n·ω) dω, 1 under open
  // sky, or for radiance V(ω) itself.
  int visibilityPerProbe = 0;
  std::vector<float> visibility;
  // Per probe, its distances to the first surface around it (volume/DistanceMoments.h):
  // distanceMap.valuesPerProbe() values, or none (size 0) in volumes without them.
  DistanceMapLayout distanceMap{0, 0.0};
  std::vector<float> distanceMoments;
  // The sky its light came from (setting "sky" names it), or none in volumes from before it was
  // kept: what relighting takes away.
  std::optional<SkyRadiance> sky;
  // Per probe: whether it was baked where the grid puts it, moved out of geometry by `offsets`
  // (world units), or found inside geometry and filled from its neighbours.
  std::vector<ProbeState> states;
  std::vector<Eigen::Vector3f> offsets;
  // What produced it (rays, scene file, ...): written to the file's metadata as it is.
  std::map<std::string, std::string> settings;
  // Set on a part of a bake cut into shards: only the shard's bricks were baked (every other
  // probe is Invalid and zero, or not held at all: `rows`), and its Invalid probes are not
  // filled until the parts are merged.
  std::optional<Shard> shard;

  // Whether files keep per-probe states: for every bake that found them, and for every shard's
  // part, even one whose shard holds no brick, since the merge reads them.
  bool hasProbeStates() const { return !states.empty() || shard.has_value(); }
  std::int64_t rowOf(std::int64_t probe) const { return rows.row(grid, probe); }
  // The coefficients of a probe the volume holds.
  const float* probe(std::int64_t index) const { return coefficients.data() + rowOf(index) * coefficientsPerProbe; }
  int distanceMomentsPerProbe() const { return distanceMap.size > 0 ? distanceMap.valuesPerProbe() : 0; }
  int skyDirectPerProbe() const { return keepsSkyDirect ? coefficientsPerProbe : 0; }
  int skyBouncedPerProbe() const { return keepsSkyBounced ? coefficientsPerProbe : 0; }

  // Every per-probe array of floats with its width, for code that moves, packs or checks rows
  // alike; the order is fixed (packing relies on it).
  template <typename Values>
  struct Rows {
    Values* values;
    int width;
  };
  std::array<Rows<std::vector<float>>, 5> floatRows() {
    return {{{&coefficients, coefficientsPerProbe},
             {&skyDirect, skyDirectPerProbe()},
             {&skyBounced, skyBouncedPerProbe()},
             {&visibility, visibilityPerProbe},
             {&distanceMoments, distanceMomentsPerProbe()}}};
  }
  std::array<Rows<const std::vector<float>>, 5> floatRows() const {
    return {{{&coefficients, coefficientsPerProbe},
             {&skyDirect, skyDirectPerProbe()},
             {&skyBounced, skyBouncedPerProbe()},
             {&visibility, visibilityPerProbe},
             {&distanceMoments, distanceMomentsPerProbe()}}};
  }
};

}  // namespace baker
