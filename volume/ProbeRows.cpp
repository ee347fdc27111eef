#include "volume/ProbeRows.h"

#include <stdexcept>

namespace baker {

ProbeRows::ProbeRows(const ProbeGrid& grid, const std::vector<std::int64_t>& bricks)
    : firstRowOfBrick_(std::size_t(grid.brickCount()), -1) {
  const Eigen::Vector3i counts = grid.brickCounts();
  for (const std::int64_t b : bricks) {
    if (b < 0 || b >= std::int64_t(firstRowOfBrick_.size()) || firstRowOfBrick_[std::size_t(b)] >= 0)
      throw std::logic_error("ProbeRows: a brick outside the grid, or listed twice");
    firstRowOfBrick_[std::size_t(b)] = rows_;
    const Eigen::Vector3i lo = kBrickSize * Eigen::Vector3i(int(b % counts.x()), int(b / counts.x() % counts.y()),
                                                            int(b / (std::int64_t(counts.x()) * counts.y())));
    const Eigen::Vector3i size = (lo.array() + kBrickSize).min(grid.dims.array()) - lo.array();
    rows_ += std::int64_t(size.x()) * size.y() * size.z();
  }
}

std::int64_t ProbeRows::row(const ProbeGrid& grid, int i, int j, int k) const {
  if (holdsEveryProbe()) return grid.linearIndex(i, j, k);
  const Eigen::Vector3i counts = grid.brickCounts();
  const int bi = i / kBrickSize, bj = j / kBrickSize, bk = k / kBrickSize;
  const std::int64_t first = firstRowOfBrick_[std::size_t(bi + std::int64_t(counts.x()) * (bj + std::int64_t(counts.y()) * bk))];
  if (first < 0) return -1;
  // Within the brick, x fastest, over the brick's own (possibly partial) extent.
  const int w = std::min(kBrickSize, grid.dims.x() - bi * kBrickSize);
  const int h = std::min(kBrickSize, grid.dims.y() - bj * kBrickSize);
  return first + (i - bi * kBrickSize) + w * ((j - bj * kBrickSize) + std::int64_t(h) * (k - bk * kBrickSize));
}

std::int64_t ProbeRows::row(const ProbeGrid& grid, std::int64_t probe) const {
  if (holdsEveryProbe()) return probe;
  if (probe < 0 || probe >= grid.probeCount()) return -1;
  const std::int64_t nx = grid.dims.x(), ny = grid.dims.y();
  return row(grid, int(probe % nx), int(probe / nx % ny), int(probe / (nx * ny)));
}

std::int64_t ProbeRows::probeAt(const ProbeGrid& grid, std::int64_t row) const {
  if (holdsEveryProbe()) return row >= 0 && row < grid.probeCount() ? row : -1;
  // A search through the grid: only an error message asks.
  for (std::int64_t p = 0; p < grid.probeCount(); ++p)
    if (this->row(grid, p) == row) return p;
  return -1;
}

}  // namespace baker
