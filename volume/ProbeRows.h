#pragma once
#include <cstdint>
#include <vector>

#include "volume/ProbeGrid.h"

namespace baker {

// Where a probe's values sit in a Volume's arrays. A whole volume holds every probe, probe p in
// row p. A volume that holds only some bricks (a shard's part as it is baked, a level of an
// adaptive volume) holds them brick after brick in the order given, each brick's probes in
// probesOfBrick order: a process holds what it bakes, not the grid.
class ProbeRows {
 public:
  ProbeRows() = default;  // every probe
  ProbeRows(const ProbeGrid& grid, const std::vector<std::int64_t>& bricks);

  bool holdsEveryProbe() const { return firstRowOfBrick_.empty(); }
  // Rows the arrays of a volume on `grid` need.
  std::int64_t count(const ProbeGrid& grid) const { return holdsEveryProbe() ? grid.probeCount() : rows_; }
  // The bricks held, in row order; empty when every probe is.
  const std::vector<std::int64_t>& bricks() const { return bricks_; }
  bool holdsBrick(std::int64_t brick) const { return holdsEveryProbe() || firstRowOfBrick_[std::size_t(brick)] >= 0; }
  // The row of probe (i, j, k) of `grid`, or -1 when it is not held.
  std::int64_t row(const ProbeGrid& grid, int i, int j, int k) const;
  std::int64_t row(const ProbeGrid& grid, std::int64_t probe) const;
  // The probe in row `row` (-1 for none).
  std::int64_t probeAt(const ProbeGrid& grid, std::int64_t row) const;

 private:
  std::vector<std::int64_t> firstRowOfBrick_;  // by linear brick index, -1 for a brick not held
  std::vector<std::int64_t> bricks_;           // held, in row order
  std::vector<std::int64_t> firstRows_;        // of bricks_[n]: increasing
  std::int64_t rows_ = 0;
};

}  // namespace baker
