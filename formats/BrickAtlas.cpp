#include "formats/BrickAtlas.h"

#include <cmath>

#include "volume/SubBricks.h"

namespace baker {

BrickAtlas BrickAtlas::of(std::vector<std::int64_t> bricks, std::vector<std::uint8_t> masks) {
  BrickAtlas atlas;
  const std::int64_t n = std::int64_t(bricks.size());
  atlas.bricks = std::move(bricks);
  atlas.masks = std::move(masks);
  if (n == 0) return atlas;
  std::int64_t side = std::max<std::int64_t>(1, std::int64_t(std::cbrt(double(n))));
  while (side * side * side < n) side += 1;
  const std::int64_t layers = (n + side * side - 1) / (side * side);
  atlas.slots = Eigen::Vector3i(int(side), int(side), int(layers));
  return atlas;
}

std::int64_t BrickAtlas::probeAt(const ProbeGrid& grid, int x, int y, int z) const {
  const std::int64_t slot =
      x / kBrickSize + std::int64_t(slots.x()) * (y / kBrickSize + std::int64_t(slots.y()) * (z / kBrickSize));
  if (slot >= std::int64_t(bricks.size())) return -1;
  const std::int64_t brick = bricks[std::size_t(slot)];
  const Eigen::Vector3i local(x % kBrickSize, y % kBrickSize, z % kBrickSize);
  if ((local.array() >= grid.brickExtent(brick).array()).any()) return -1;
  if (!masks.empty() && !(masks[std::size_t(slot)] & subBrickBit(local.x(), local.y(), local.z()))) return -1;
  const Eigen::Vector3i probe = grid.brickCorner(brick) + local;
  return grid.linearIndex(probe.x(), probe.y(), probe.z());
}

}  // namespace baker
