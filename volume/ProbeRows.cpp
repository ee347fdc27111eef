#include "volume/ProbeRows.h"

#include <algorithm>
#include <stdexcept>

namespace baker {

ProbeRows::ProbeRows(const ProbeGrid& grid, const std::vector<std::int64_t>& bricks)
    : firstRowOfBrick_(std::size_t(grid.brickCount()), -1), bricks_(bricks) {
  firstRows_.reserve(bricks.size());
  for (const std::int64_t b : bricks) {
    if (b < 0 || b >= std::int64_t(firstRowOfBrick_.size()) || firstRowOfBrick_[std::size_t(b)] >= 0)
      throw std::logic_error("ProbeRows: a brick outside the grid, or listed twice");
    firstRowOfBrick_[std::size_t(b)] = rows_;
    firstRows_.push_back(rows_);
    rows_ += grid.brickExtent(b).cast<std::int64_t>().prod();
  }
}

ProbeRows::ProbeRows(const ProbeGrid& grid, const std::vector<std::int64_t>& bricks, const std::vector<std::uint8_t>& masks)
    : ProbeRows(grid, bricks) {
  if (masks.size() != bricks.size()) throw std::logic_error("ProbeRows: a mask per brick");
  for (std::size_t n = 0; n < bricks.size(); ++n) {
    const std::uint8_t inGrid = subBricksInGrid(grid, bricks[n]);
    if ((masks[n] & inGrid) == 0) throw std::logic_error("ProbeRows: a brick holding no sub-brick");
    partial_ |= (masks[n] & inGrid) != inGrid;
  }
  if (!partial_) return;
  maskOfBrick_.assign(firstRowOfBrick_.size(), 0);
  for (std::size_t n = 0; n < bricks.size(); ++n)
    maskOfBrick_[std::size_t(bricks[n])] = std::uint8_t(masks[n] & subBricksInGrid(grid, bricks[n]));
}

std::uint8_t ProbeRows::subBricks(const ProbeGrid& grid, std::int64_t brick) const {
  if (!holdsBrick(brick)) return 0;
  return partial_ ? maskOfBrick_[std::size_t(brick)] : subBricksInGrid(grid, brick);
}

std::vector<std::uint8_t> ProbeRows::masks(const ProbeGrid& grid) const {
  std::vector<std::uint8_t> masks;
  masks.reserve(bricks_.size());
  for (const std::int64_t b : bricks_) masks.push_back(subBricks(grid, b));
  return masks;
}

std::int64_t ProbeRows::probesHeld(const ProbeGrid& grid, std::int64_t brick) const {
  const Eigen::Vector3i extent = grid.brickExtent(brick);
  if (!partial_) return holdsBrick(brick) ? extent.cast<std::int64_t>().prod() : 0;
  const std::uint8_t mask = maskOfBrick_[std::size_t(brick)];
  std::int64_t probes = 0;
  for (int s = 0; s < 8; ++s)
    if (mask & (1u << s)) {
      const auto side = [&](int axis, bool upper) {
        return std::int64_t(upper ? extent[axis] - kSubBrickSize : std::min(extent[axis], kSubBrickSize));
      };
      probes += side(0, s & 1) * side(1, s & 2) * side(2, s & 4);
    }
  return probes;
}

std::int64_t ProbeRows::probesHeld(const ProbeGrid& grid) const {
  if (!partial_) return count(grid);
  std::int64_t probes = 0;
  for (const std::int64_t b : bricks_) probes += probesHeld(grid, b);
  return probes;
}

std::int64_t ProbeRows::row(const ProbeGrid& grid, int i, int j, int k) const {
  if (holdsEveryProbe()) return grid.linearIndex(i, j, k);
  const std::int64_t brick = grid.brickOf(i, j, k);
  const std::int64_t first = firstRowOfBrick_[std::size_t(brick)];
  if (first < 0) return -1;
  if (partial_ && !(maskOfBrick_[std::size_t(brick)] & subBrickBit(i, j, k))) return -1;
  // Within the brick, x fastest, over the brick's own (possibly partial) extent.
  const Eigen::Vector3i lo = grid.brickCorner(brick), size = grid.brickExtent(brick);
  return first + (i - lo.x()) + size.x() * ((j - lo.y()) + std::int64_t(size.y()) * (k - lo.z()));
}

std::int64_t ProbeRows::row(const ProbeGrid& grid, std::int64_t probe) const {
  if (holdsEveryProbe()) return probe;
  if (probe < 0 || probe >= grid.probeCount()) return -1;
  const std::int64_t nx = grid.dims.x(), ny = grid.dims.y();
  return row(grid, int(probe % nx), int(probe / nx % ny), int(probe / (nx * ny)));
}

std::int64_t ProbeRows::probeAt(const ProbeGrid& grid, std::int64_t row) const {
  if (holdsEveryProbe()) return row >= 0 && row < grid.probeCount() ? row : -1;
  if (row < 0 || row >= rows_) return -1;
  const std::size_t n = std::size_t(std::upper_bound(firstRows_.begin(), firstRows_.end(), row) - firstRows_.begin()) - 1;
  const Eigen::Vector3i lo = grid.brickCorner(bricks_[n]), size = grid.brickExtent(bricks_[n]);
  const std::int64_t local = row - firstRows_[n];
  const std::int64_t area = std::int64_t(size.x()) * size.y();
  return grid.linearIndex(lo.x() + int(local % size.x()), lo.y() + int(local % area / size.x()), lo.z() + int(local / area));
}

}  // namespace baker
