#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "volume/AdaptiveVolume.h"

namespace baker {

// An adaptive bake cut into shards, put together from its parts in any order: each level's
// bricks from the part that traced them, then finishAdaptiveLevels as the one-process bake runs
// it, so the result is the same bits. Each part is checked against the first before it is kept
// (VolumeAssembly's checks on level 0, then the levels' grids, the margin and the placement); a
// mismatch is an InputError naming the part and the field. Holds the parts until finish(), then
// the whole volume: about twice the volume at its peak.
class AdaptiveAssembly {
 public:
  AdaptiveAssembly(const AdaptiveVolume& first, const std::string& firstName);

  void add(AdaptiveVolume part, const std::string& name);
  // Every shard given, and their bricks together the placement every part records: the finished
  // volume. InputError naming what is missing or given twice otherwise.
  AdaptiveVolume finish();

 private:
  std::vector<std::pair<std::int64_t, std::size_t>> owners(int index) const;
  Volume level(int index, const std::vector<std::pair<std::int64_t, std::size_t>>& owners);
  void requireBorderStates(const Volume& level, int index, const ProbeRows& placed,
                           const std::vector<std::pair<std::int64_t, std::size_t>>& owners) const;

  AdaptiveVolume first_;  // the first part's grids, settings and placement (no values)
  std::string firstName_;
  std::vector<AdaptiveVolume> parts_;
  std::vector<std::string> names_;
  std::vector<std::string> given_;  // per shard: the part that holds it, "" until given
};

}  // namespace baker
