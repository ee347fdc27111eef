#pragma once
#include <cstdint>
#include <functional>
#include <optional>

#include "bake/AdaptivePlacement.h"
#include "bake/Baker.h"
#include "volume/AdaptiveVolume.h"
#include "volume/Shard.h"

namespace baker {

// Bakes the levels of `placement`, coarsest first, each as bakeVolume bakes a grid, with these
// differences:
//  - a probe of a finer level on the border of its level's bricks (a neighbour of its 26 inside
//    the level's grid is not placed) is not traced: it takes the coarser levels' interpolated
//    value there (ProbeState::Interpolated), as engines do, so that interpolated irradiance is
//    continuous where the level changes (docs/ADAPTIVE.md gives the argument);
//  - the finest level's probe p draws the random stream of a uniform bake's probe p on the same
//    grid, and a coarser level's those after every finer level's, so no two probes share one;
//  - Invalid probes are filled from their own level's neighbours;
//  - a level then keeps only the bricks worth storing (StoredBricks.h), before finer levels read
//    it, so that its border probes take what a reader of the file samples.
// The result depends on the settings' seed, not on the number of threads.
// With `shard`, only the shard's share of the levels' bricks (shardLevelBricks) is traced and
// nothing is finished: a part (AdaptiveVolume::placement) whose probes are the same bits as in the
// whole bake; finishAdaptiveLevels runs when the parts are put together (AdaptiveAssembly).
AdaptiveVolume bakeAdaptive(const Scene& scene, const RayTracer& tracer, const Basis& basis,
                            const AdaptivePlacement& placement, const BakeSettings& settings, BakeStats* stats,
                            const std::function<void(std::int64_t, std::int64_t)>& progress = {},
                            const std::optional<Shard>& shard = std::nullopt);

}  // namespace baker
