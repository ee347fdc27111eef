#pragma once
#include <cstdint>
#include <vector>

#include "volume/Volume.h"

namespace baker {

// Which bricks of 8³ probes a file keeps: those the volume holds with a probe traced outside
// geometry (Valid or Relocated), or next to one (one of its 26 neighbours) in another brick.
// Every interpolation cell with a traced corner outside geometry then has all eight corners
// stored, so that an engine never blends a filled probe's light with the zeros of a brick left
// out; a cell whose corners all lie inside geometry, or are an adaptive level's border probes
// (which hold the coarser levels' values, what a point falling back to them gets), may lose its
// corners. By linear brick index; every brick when the volume has no probe states.
std::vector<bool> bricksWorthStoring(const Volume& volume);

// The bricks holding a probe traced outside geometry: what a shard's part of a uniform bake keeps, whose neighbours in
// other shards are not baked yet.
std::vector<bool> bricksWithAProbeOutsideGeometry(const Volume& volume);

// The bricks `volume` holds, in increasing order.
std::vector<std::int64_t> heldBricksInOrder(const Volume& volume);

// `volume` holding only the bricks `keep` marks among those it holds, in the order it holds them,
// each with the sub-bricks it holds.
Volume keepBricks(Volume volume, const std::vector<bool>& keep);

}  // namespace baker
