#pragma once
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "volume/ProbeGrid.h"

namespace baker {

// Some bricks of a grid packed side by side into a 3D texture of whole bricks (8³ texels each):
// how a level of an adaptive volume is stored in EXR slices, and how a GPU holds it, with an
// indirection texture from the level's bricks to their slots. Slot s (x fastest, then y, then z)
// holds brick bricks[s]; texel t of its slot is probe brickCorner + t. Texels beyond a brick cut
// by the grid's edge, and slots past the last brick, hold no probe.
struct BrickAtlas {
  Eigen::Vector3i slots = Eigen::Vector3i::Zero();  // along x, y, z
  std::vector<std::int64_t> bricks;                 // linear brick indices of the grid, increasing
  // Per brick, its sub-bricks held (volume/SubBricks.h); empty when every brick is whole. The
  // texels of the others hold no probe.
  std::vector<std::uint8_t> masks;

  // The bricks in a near-cubic atlas: ⌈∛n⌉ slots along x and y, as many layers along z as needed,
  // so that every side stays within a GPU's 3D texture limit (2048 texels) up to 2^24 bricks.
  static BrickAtlas of(std::vector<std::int64_t> bricks, std::vector<std::uint8_t> masks = {});
  Eigen::Vector3i texels() const { return slots * kBrickSize; }
  // The probe of `grid` at texel (x, y, z), or -1 when the texel holds none.
  std::int64_t probeAt(const ProbeGrid& grid, int x, int y, int z) const;
};

}  // namespace baker
