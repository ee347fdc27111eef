#include "volume/ProbeRows.h"

#include <algorithm>
#include <stdexcept>

namespace baker {

namespace {

// Probes along one axis of a brick of that extent in its lower (half 0) or upper (half 1) sub-brick.
int subBrickSide(int extent, int half) { return half ? std::max(extent - kSubBrickSize, 0) : std::min(extent, kSubBrickSize); }

Eigen::Vector3i subBrickExtent(const Eigen::Vector3i& brickExtent, int s) {
  return {subBrickSide(brickExtent.x(), s & 1), subBrickSide(brickExtent.y(), (s >> 1) & 1),
          subBrickSide(brickExtent.z(), (s >> 2) & 1)};
}

// The probes of the sub-bricks `mask` holds before sub-brick `s` (all of them for s = 8).
std::int64_t probesBefore(const Eigen::Vector3i& brickExtent, std::uint8_t mask, int s) {
  std::int64_t probes = 0;
  for (int t = 0; t < s; ++t)
    if (mask & (1u << t)) probes += subBrickExtent(brickExtent, t).cast<std::int64_t>().prod();
  return probes;
}

}  // namespace

ProbeRows::ProbeRows(const ProbeGrid& grid, const std::vector<std::int64_t>& bricks) : ProbeRows(grid, bricks, nullptr) {}

ProbeRows::ProbeRows(const ProbeGrid& grid, const std::vector<std::int64_t>& bricks, const std::vector<std::uint8_t>& masks)
    : ProbeRows(grid, bricks, &masks) {}

ProbeRows::ProbeRows(const ProbeGrid& grid, const std::vector<std::int64_t>& bricks, const std::vector<std::uint8_t>* masks)
    : firstRowOfBrick_(std::size_t(grid.brickCount()), -1), bricks_(bricks) {
  if (masks && masks->size() != bricks.size()) throw std::logic_error("ProbeRows: a mask per brick");
  for (std::size_t n = 0; masks && n < bricks.size(); ++n) {
    if (bricks[n] < 0 || bricks[n] >= grid.brickCount()) throw std::logic_error("ProbeRows: a brick outside the grid");
    const std::uint8_t inGrid = subBricksInGrid(grid, bricks[n]);
    if (((*masks)[n] & inGrid) == 0) throw std::logic_error("ProbeRows: a brick holding no sub-brick");
    partial_ |= ((*masks)[n] & inGrid) != inGrid;
  }
  if (partial_) maskOfBrick_.assign(firstRowOfBrick_.size(), 0);
  firstRows_.reserve(bricks.size());
  for (std::size_t n = 0; n < bricks.size(); ++n) {
    const std::int64_t b = bricks[n];
    if (b < 0 || b >= std::int64_t(firstRowOfBrick_.size()) || firstRowOfBrick_[std::size_t(b)] >= 0)
      throw std::logic_error("ProbeRows: a brick outside the grid, or listed twice");
    if (partial_) maskOfBrick_[std::size_t(b)] = std::uint8_t((*masks)[n] & subBricksInGrid(grid, b));
    firstRowOfBrick_[std::size_t(b)] = rows_;
    firstRows_.push_back(rows_);
    rows_ += probesHeld(grid, b);
  }
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
  return probesBefore(extent, maskOfBrick_[std::size_t(brick)], 8);
}

std::int64_t ProbeRows::row(const ProbeGrid& grid, int i, int j, int k) const {
  if (holdsEveryProbe()) return grid.linearIndex(i, j, k);
  const std::int64_t brick = grid.brickOf(i, j, k);
  const std::int64_t first = firstRowOfBrick_[std::size_t(brick)];
  if (first < 0) return -1;
  const Eigen::Vector3i lo = grid.brickCorner(brick), size = grid.brickExtent(brick);
  const Eigen::Vector3i local(i - lo.x(), j - lo.y(), k - lo.z());
  if (!partial_) return first + local.x() + size.x() * (local.y() + std::int64_t(size.y()) * local.z());
  // Sub-brick after sub-brick, each x fastest over its own extent.
  const std::uint8_t mask = maskOfBrick_[std::size_t(brick)], bit = subBrickBit(i, j, k);
  if (!(mask & bit)) return -1;
  const int s = (local.x() >= kSubBrickSize) + 2 * (local.y() >= kSubBrickSize) + 4 * (local.z() >= kSubBrickSize);
  const Eigen::Vector3i in = local - kSubBrickSize * Eigen::Vector3i(s & 1, (s >> 1) & 1, (s >> 2) & 1);
  const Eigen::Vector3i sub = subBrickExtent(size, s);
  return first + probesBefore(size, mask, s) + in.x() + sub.x() * (in.y() + std::int64_t(sub.y()) * in.z());
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
  const std::int64_t brick = bricks_[n];
  const Eigen::Vector3i lo = grid.brickCorner(brick), size = grid.brickExtent(brick);
  std::int64_t local = row - firstRows_[n];
  Eigen::Vector3i corner = lo, extent = size;
  if (partial_) {
    const std::uint8_t mask = maskOfBrick_[std::size_t(brick)];
    for (int s = 0; s < 8; ++s) {
      if (!(mask & (1u << s))) continue;
      extent = subBrickExtent(size, s);
      if (local < extent.cast<std::int64_t>().prod()) {
        corner = lo + kSubBrickSize * Eigen::Vector3i(s & 1, (s >> 1) & 1, (s >> 2) & 1);
        break;
      }
      local -= extent.cast<std::int64_t>().prod();
    }
  }
  const std::int64_t area = std::int64_t(extent.x()) * extent.y();
  return grid.linearIndex(corner.x() + int(local % extent.x()), corner.y() + int(local % area / extent.x()),
                          corner.z() + int(local / area));
}

}  // namespace baker
