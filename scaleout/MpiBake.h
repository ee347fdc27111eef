#pragma once
#include <cstdint>
#include <vector>

#include "bake/BakeJob.h"
#include "formats/EngineExport.h"
#include "formats/VolumeWriter.h"
#include "scaleout/MpiSession.h"

namespace baker {

// The worker threads a rank takes when the request leaves it open: this machine's cores shared
// by the ranks running on it, so that ranks do not oversubscribe it.
int threadsPerRank(const MpiSession& session, int requestedThreads);

// What one rank did, as rank 0 reports it.
struct RankReport {
  int rank = 0;
  int threads = 0;
  std::int64_t probes = 0, raysTraced = 0;
  double bakeSeconds = 0.0;
  double peakMemoryBytes = 0.0;
};

struct MpiBakeReport {
  BakeStats stats;                // this rank's own shard
  double bakeSeconds = 0.0;       // this rank's shard
  // On rank 0 only:
  std::vector<RankReport> ranks;  // every rank, in rank order
  std::int64_t probes = 0, validProbes = 0, relocatedProbes = 0, invalidProbes = 0, raysTraced = 0;
  EngineExport engineExport;
  double gatherSeconds = 0.0, writeSeconds = 0.0;
};

// Every rank calls this with its job, made from the same request with shard rank/size: the rank
// bakes its shard; rank 0 receives every other rank's bricks, fills the invalid probes over the
// whole grid and writes `output`: the bytes the one-process bake writes. Ranks other than 0
// write nothing. `progress` hears this rank's bricks.
MpiBakeReport bakeWithMpi(const MpiSession& session, const BakeJob& job, const VolumeOutput& output,
                          const std::function<void(std::int64_t, std::int64_t)>& progress = {});

}  // namespace baker
