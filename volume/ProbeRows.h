#pragma once
#include <cstdint>
#include <vector>

#include "volume/ProbeGrid.h"

namespace baker {

// Where a probe's values sit in a Volume's arrays. A whole volume holds every probe, probe p in
// row p. A shard's part, as it is baked, holds only its own bricks, brick after brick in the
// order given, each brick's probes in probesOfBrick order: a process holds what it bakes, not
// the grid.
class ProbeRows {
 public:
  ProbeRows() = default;  // every probe
  ProbeRows(const ProbeGrid& grid, const std::vector<std::int64_t>& bricks);

  bool holdsEveryProbe() const { return firstRowOfBrick_.empty(); }
  // Rows the arrays of a volume on `grid` need.
  std::int64_t count(const ProbeGrid& grid) const { return holdsEveryProbe() ? grid.probeCount() : rows_; }
  // The row of probe (i, j, k) of `grid`, or -1 when it is not held.
  std::int64_t row(const ProbeGrid& grid, int i, int j, int k) const;
  std::int64_t row(const ProbeGrid& grid, std::int64_t probe) const;
  // The probe in row `row` (-1 for none): for messages, which name probes, not rows.
  std::int64_t probeAt(const ProbeGrid& grid, std::int64_t row) const;

 private:
  std::vector<std::int64_t> firstRowOfBrick_;  // by linear brick index, -1 for a brick not held
  std::int64_t rows_ = 0;
};

}  // namespace baker
