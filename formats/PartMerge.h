#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "formats/EngineExport.h"
#include "formats/VolumeWriter.h"

namespace baker {

struct MergeReport {
  int shards = 0;
  int levels = 1;  // of an adaptive bake's volume
  std::int64_t probes = 0, invalidProbes = 0;  // held in every level; invalid probes are filled by the merge
  std::string basis;
  EngineExport engineExport;  // when the output is an engine's format
  double readSeconds = 0.0, writeSeconds = 0.0;
};

// `baker merge`: reads the parts of a bake cut into shards (`--shard K/N`; OpenVDB files or EXR
// slice directories, in any order and mix), checks that they are one bake and every shard
// appears exactly once (VolumeAssembly), fills the invalid probes over the whole grid and writes
// the volume to `output`: the same bytes the one-process bake writes with the same settings.
// The parts of an adaptive bake (levels) are put together by AdaptiveAssembly, and a uniform part
// among them is refused as not of the bake.
// InputError naming the part and the field on any mismatch; nothing is written then.
MergeReport mergeParts(const std::vector<std::string>& parts, const VolumeOutput& output);

}  // namespace baker
