#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "basis/BasisParameters.h"
#include "basis/GramOperators.h"
#include "scene/SceneOptions.h"
#include "volume/DistanceMoments.h"
#include "volume/LevelGrids.h"
#include "volume/Shard.h"

namespace baker {

// The library's limits and defaults for a bake, each defined here once.
constexpr int kMaxRaysPerProbe = 1 << 20;
constexpr std::int64_t kMaxBakeProbes = std::int64_t(1) << 27;  // a grid beyond it is refused before tracing
constexpr int kMaxBounces = 64;
constexpr int kDefaultBounces = 3;
constexpr int kMinDistanceMap = 2, kMaxDistanceMap = 16;
constexpr const char* kDefaultBasis = "sh-l2";
constexpr const char* kDefaultQuality = "default";

// Everything that decides a bake, as plain values: what the command line, a script, a
// benchmark or a test fills in. Errors name these fields (SettingError::setting), in
// snake_case: "spacing", "rays", "sg_sharpness", ...
struct BakeRequest {
  std::string scenePath;
  SceneOptions scene;                  // glTF scene index and environment
  std::string basis = kDefaultBasis;   // a name of basisNames()
  std::optional<double> sgSharpness;   // λ of sg-N lobes; none: the measured default
  std::optional<Eigen::Vector3d> hemisphereAxis;  // up of ad-hemi9's hemisphere; none: +Y
  std::optional<double> spacing;       // metres; none: the scene's longest side / 16
  // A preset of qualityPresets(): each probe traces until its error is under the preset's
  // target. Empty: every probe traces `rays` directions, no more and no fewer.
  std::string quality = kDefaultQuality;
  int rays = 256;
  // Metres: the probes of a brick share what their paths bring back from surfaces, averaged
  // over cells of this side (bake/SharedReflections.h). Fixed ray counts only; 0: each probe
  // keeps its own.
  double sharedReflectionCell = 0.0;
  static constexpr double kMinSharedReflectionCell = 1e-4, kMaxSharedReflectionCell = 1e4;
  int bounces = kDefaultBounces;
  std::uint64_t seed = 0;
  int threads = 0;                     // 0: every core; the result does not depend on it
  std::vector<std::string> turnedOff;  // effects not to simulate (keys of the plan)
  BandWindow window;                   // Hann window on the SH bands before projecting
  bool nonNegative = false;            // coefficients >= 0 by a per-probe constrained solve
  // What the coefficients hold: "irradiance" (E(n), one lookup per normal) or "radiance" (L(ω),
  // from which readers reconstruct irradiance by each function's diffuse response; basis/StoredSignal.h).
  std::string signal = "irradiance";
  // Texels per side of each probe's map of distances to the first surface, for leak-aware
  // sampling (volume/DistanceMoments.h); 0: none. Uniform placement only; none given: the
  // default size for uniform placement, none for adaptive.
  std::optional<int> distanceMap;
  // Bake only this shard's bricks (volume/Shard.h), a part for merging; none: the whole grid.
  std::optional<Shard> shard;
  // "uniform": one grid at `spacing`. "adaptive": `levels` nested levels (volume/LevelGrids.h),
  // the finest at `spacing`, its bricks placed near geometry (bake/AdaptivePlacement.h).
  std::string placement = "uniform";
  int levels = 3;
  int marginCells = kDefaultMarginCells;

  bool adaptive() const { return placement == "adaptive"; }
  BasisParameters basisParameters() const { return {sgSharpness, hemisphereAxis}; }
  int distanceMapSize() const { return distanceMap.value_or(adaptive() ? 0 : DistanceMapLayout::kDefaultSize); }
};

// Every check that needs no scene: values in range, names known, combinations that make sense.
// SettingError naming the field otherwise. Run by BakeJob before anything is loaded.
void validateBakeRequest(const BakeRequest& request);

// The `quality` a volume records: the preset, or "fixed" for a fixed ray count.
std::string qualityName(const BakeRequest& request);

}  // namespace baker
