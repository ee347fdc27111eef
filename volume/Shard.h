#pragma once
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "volume/ProbeGrid.h"

namespace baker {

// The most shards one bake may be cut into.
constexpr int kMaxShards = 4096;

// Shard `index` of `count` of a bake: a contiguous run of the grid's bricks in Morton order
// (shardBricks), so that one shard's probes are near one another and its rays stay coherent.
struct Shard {
  int index = 0;
  int count = 1;
  bool operator==(const Shard& other) const { return index == other.index && count == other.count; }
};

// "K/N", as the command line, the files and the reports write a shard.
std::string shardName(const Shard& shard);
// The shard "K/N" names, or none unless it is exactly two whole numbers with 0 <= K < N <= kMaxShards.
std::optional<Shard> parseShard(const std::string& text);

// Every brick of `grid` (ProbeGrid::brickCounts, linear index bx + Bx·(by + By·bz)) in Morton
// order of its brick coordinates: the bits of x, y and z interleaved, so that each run of the
// order stays in a compact region.
std::vector<std::int64_t> bricksInMortonOrder(const ProbeGrid& grid);

// The bricks of `shard`: run [⌊K·B/N⌋, ⌊(K+1)·B/N⌋) of the Morton order of the B bricks, so
// that the shards hold every brick exactly once. A shard of a grid with fewer bricks than
// shards may hold none.
std::vector<std::int64_t> shardBricks(const ProbeGrid& grid, const Shard& shard);

// The bricks of `shard` of an adaptive bake, per level: every level's placed bricks (`placed`, per
// level by increasing index), coarsest level first and each level's in the Morton order of its
// grid, cut as shardBricks cuts one grid's bricks. Per level by increasing index.
std::vector<std::vector<std::int64_t>> shardLevelBricks(const std::vector<ProbeGrid>& grids,
                                                        const std::vector<std::vector<std::int64_t>>& placed,
                                                        const Shard& shard);
// shardLevelBricks of every shard of `count` at once (for MPI's rank 0): [shard][level].
std::vector<std::vector<std::vector<std::int64_t>>> everyShardsLevelBricks(
    const std::vector<ProbeGrid>& grids, const std::vector<std::vector<std::int64_t>>& placed, int count);
// How many of each level's placed bricks (`placedPerLevel`) shard `shard`'s share holds.
std::vector<std::int64_t> shardLevelBrickCounts(const std::vector<std::int64_t>& placedPerLevel, const Shard& shard);

// Which shard of `count` holds each brick of `grid` (indexed by linear brick index).
std::vector<int> shardOfBricks(const ProbeGrid& grid, int count);

// The probes of brick `brick` (linear brick index) in ProbeGrid::linearIndex order, the last
// brick on each axis possibly partial.
std::vector<std::int64_t> probesOfBrick(const ProbeGrid& grid, std::int64_t brick);

// 16 hex digits of FNV-1a over the basis name, the grid and every setting that made a volume:
// two parts of one bake have the same fingerprint, parts of different bakes (almost surely) not.
std::string bakeFingerprint(const std::string& basisName, const ProbeGrid& grid,
                            const std::map<std::string, std::string>& settings);

}  // namespace baker
