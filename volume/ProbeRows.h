#pragma once
#include <cstdint>
#include <vector>

#include "volume/ProbeGrid.h"
#include "volume/SubBricks.h"

namespace baker {

// Where a probe's values sit in a Volume's arrays. A whole volume holds every probe, probe p in
// row p. A volume that holds only some bricks (a shard's part as it is baked, a level of an
// adaptive volume) holds them brick after brick in the order given, each brick's probes x fastest
// over its extent: a process holds what it bakes, not the grid. A brick may hold only some of its
// sub-bricks (SubBricks.h: an adaptive level's placement); then only their probes have rows, each
// brick's held sub-bricks one after another in sub-brick order, each x fastest.
class ProbeRows {
 public:
  ProbeRows() = default;  // every probe
  ProbeRows(const ProbeGrid& grid, const std::vector<std::int64_t>& bricks);
  // `masks[n]`: the sub-bricks held of bricks[n], none of them 0.
  ProbeRows(const ProbeGrid& grid, const std::vector<std::int64_t>& bricks, const std::vector<std::uint8_t>& masks);

  bool holdsEveryProbe() const { return firstRowOfBrick_.empty(); }
  // Rows the arrays of a volume on `grid` need: one per probe held.
  std::int64_t count(const ProbeGrid& grid) const { return holdsEveryProbe() ? grid.probeCount() : rows_; }
  // The bricks held, in row order; empty when every probe is.
  const std::vector<std::int64_t>& bricks() const { return bricks_; }
  bool holdsBrick(std::int64_t brick) const { return holdsEveryProbe() || firstRowOfBrick_[std::size_t(brick)] >= 0; }
  // The sub-bricks held of `brick` (0 when it is not held), within subBricksInGrid.
  std::uint8_t subBricks(const ProbeGrid& grid, std::int64_t brick) const;
  // Per brick of bricks(), its sub-bricks held.
  std::vector<std::uint8_t> masks(const ProbeGrid& grid) const;
  // Whether some held brick lacks a sub-brick.
  bool holdsPartialBricks() const { return partial_; }
  // How many probes of `brick` are held (its rows).
  std::int64_t probesHeld(const ProbeGrid& grid, std::int64_t brick) const;
  // The row of probe (i, j, k) of `grid`, or -1 when it is not held.
  std::int64_t row(const ProbeGrid& grid, int i, int j, int k) const;
  std::int64_t row(const ProbeGrid& grid, std::int64_t probe) const;
  // The first of the probesHeld rows of a held brick; -1 when the brick is not held. Not for a
  // volume holding every probe.
  std::int64_t firstRowOfBrick(std::int64_t brick) const { return firstRowOfBrick_[std::size_t(brick)]; }
  // The probe in row `row` (-1 for none).
  std::int64_t probeAt(const ProbeGrid& grid, std::int64_t row) const;

 private:
  ProbeRows(const ProbeGrid& grid, const std::vector<std::int64_t>& bricks, const std::vector<std::uint8_t>* masks);

  std::vector<std::int64_t> firstRowOfBrick_;  // by linear brick index, -1 for a brick not held
  std::vector<std::int64_t> bricks_;           // held, in row order
  std::vector<std::int64_t> firstRows_;        // of bricks_[n]: increasing
  std::vector<std::uint8_t> maskOfBrick_;      // by linear brick index, when partial_
  std::int64_t rows_ = 0;
  bool partial_ = false;
};

// f(i, j, k, row) for each probe of `brick` that `rows` holds, x fastest.
template <typename F>
void forEachHeldProbeOfBrick(const ProbeGrid& grid, const ProbeRows& rows, std::int64_t brick, F&& f) {
  const Eigen::Vector3i lo = grid.brickCorner(brick), hi = lo + grid.brickExtent(brick);
  for (int k = lo.z(); k < hi.z(); ++k)
    for (int j = lo.y(); j < hi.y(); ++j)
      for (int i = lo.x(); i < hi.x(); ++i)
        if (const std::int64_t row = rows.row(grid, i, j, k); row >= 0) f(i, j, k, row);
}

}  // namespace baker
