#include "bake/BakeRequest.h"

#include <fmt/format.h>

#include <cmath>

#include "bake/ProbeConvergence.h"
#include "bake/TransportPlan.h"
#include "basis/BasisRegistry.h"
#include "basis/StoredSignal.h"
#include "common/Error.h"

namespace baker {

void validateBakeRequest(const BakeRequest& r) {
  if (r.spacing && !(*r.spacing > 0.0 && std::isfinite(*r.spacing)))
    throw SettingError("spacing", fmt::format("must be a positive number of metres, got {}", *r.spacing));
  if (r.quality.empty() && (r.rays <= 0 || r.rays > kMaxRaysPerProbe))
    throw SettingError("rays", fmt::format("must be in 1..{}, got {}", kMaxRaysPerProbe, r.rays));
  if (!r.quality.empty() && !findQualityPreset(r.quality))
    throw SettingError("quality", fmt::format("must be one of {}, got '{}'", qualityPresetNames(), r.quality));
  if (r.bounces < 0 || r.bounces > kMaxBounces)
    throw SettingError("bounces", fmt::format("must be in 0..{}, got {}", kMaxBounces, r.bounces));
  if (r.threads < 0) throw SettingError("threads", fmt::format("must be positive, got {}", r.threads));
  if (r.window.hannWidth < 0)
    throw SettingError("window", fmt::format("must be a band count >= 1, got {}", r.window.hannWidth));
  if (r.shard && !(r.shard->count >= 1 && r.shard->count <= kMaxShards && r.shard->index >= 0 &&
                   r.shard->index < r.shard->count))
    throw SettingError("shard", fmt::format("must be K/N with 0 <= K < N <= {}, got {}", kMaxShards,
                                            shardName(*r.shard)));
  if (r.placement != "uniform" && r.placement != "adaptive")
    throw SettingError("placement", fmt::format("must be uniform or adaptive, got '{}'", r.placement));
  if (r.levels < 1 || r.levels > kMaxLevels)
    throw SettingError("levels", fmt::format("must be in 1..{}, got {}", kMaxLevels, r.levels));
  if (r.marginCells < kMinMarginCells || r.marginCells > kMaxMarginCells)
    throw SettingError("margin", fmt::format("must be in {}..{} cells, got {}", kMinMarginCells, kMaxMarginCells, r.marginCells));
  if (r.adaptive() && r.shard && r.levels < 2)
    throw SettingError("shard", "an adaptive bake of one level is written as a uniform volume and is not cut into "
                                "shards; bake 2 or more levels, or bake it whole");
  if (const int n = r.distanceMapSize(); n != 0 && (n < kMinDistanceMap || n > kMaxDistanceMap))
    throw SettingError("distance_map", fmt::format("must be 0 (none) or {}..{} texels per side, got {}", kMinDistanceMap,
                                                   kMaxDistanceMap, n));
  if (r.distanceMapSize() != 0 && r.adaptive())
    throw SettingError("distance_map", "applies to uniform placement only: adaptive volumes hold no distance maps yet");
  const double cell = r.sharedReflectionCell, least = BakeRequest::kMinSharedReflectionCell,
               most = BakeRequest::kMaxSharedReflectionCell;
  if (!(cell == 0.0 || (cell >= least && cell <= most)))
    throw SettingError("share_reflections",
                       fmt::format("must be a side in metres from {} to {} (or 0: none), got {}", least, most, cell));
  if (r.sharedReflectionCell > 0.0 && !r.quality.empty())
    throw SettingError("share_reflections", "needs a fixed ray count: a quality preset decides each probe's "
                                                 "rays from its own noise, which sharing changes");
  const StoredSignal signal = parseStoredSignal(r.signal);
  if (signal == StoredSignal::Radiance && r.window.hannWidth > 0)
    throw SettingError("window", "fades the SH bands of the irradiance fit; a radiance volume fits the samples in "
                                 "the basis directly and has no SH bands to fade");
  requireKnownEffects(r.turnedOff);
  const std::unique_ptr<Basis> basis = makeBasis(r.basis, r.basisParameters());
  if (basis->hemisphere() && signal != StoredSignal::Radiance)
    throw SettingError("signal", fmt::format("must be radiance for {}: it holds the radiance over one hemisphere, "
                                             "from which no irradiance for every normal follows",
                                             r.basis));
  if (r.nonNegative && !admitsNonNegativeFit(*basis))
    throw SettingError("non_negative",
                       fmt::format("does not apply to {}: its functions change sign, so coefficients >= 0 do not make "
                                   "the reconstruction non-negative (and can make its ringing worse); bases it "
                                   "applies to: {}",
                                   r.basis, fmt::join(nonNegativeBasisNames(), ", ")));
}

std::string qualityName(const BakeRequest& request) { return request.quality.empty() ? "fixed" : request.quality; }

}  // namespace baker
