#pragma once
#include <cstdint>

#include "volume/ProbeGrid.h"

namespace baker {

// A brick of 8³ probes is eight sub-bricks of 4³: sub-brick s = sx + 2·sy + 4·sz holds the
// brick's probes with (i / 4) % 2 = sx along x, and so on. An adaptive level places and stores
// sub-bricks (docs/ADAPTIVE.md), a brick keeping the unit of work and an OpenVDB leaf; which
// sub-bricks a brick holds is a mask of 8 bits, bit s for sub-brick s.
constexpr int kSubBrickSize = kBrickSize / 2;
constexpr std::uint8_t kEverySubBrick = 0xFF;

// The bit of the sub-brick holding probe (i, j, k), within its brick.
inline std::uint8_t subBrickBit(int i, int j, int k) {
  return std::uint8_t(1u << (((i / kSubBrickSize) & 1) + 2 * ((j / kSubBrickSize) & 1) + 4 * ((k / kSubBrickSize) & 1)));
}

// The sub-bricks of `brick` that hold a probe of `grid`: fewer than eight in the last brick of an
// axis of 4 or fewer probes there. A mask is kept as its bits within these, so that equal
// placements have equal masks.
inline std::uint8_t subBricksInGrid(const ProbeGrid& grid, std::int64_t brick) {
  const Eigen::Vector3i extent = grid.brickExtent(brick);
  std::uint8_t mask = 0;
  for (int s = 0; s < 8; ++s)
    if ((s & 1 ? extent.x() > kSubBrickSize : true) && (s & 2 ? extent.y() > kSubBrickSize : true) &&
        (s & 4 ? extent.z() > kSubBrickSize : true))
      mask = std::uint8_t(mask | (1u << s));
  return mask;
}

}  // namespace baker
