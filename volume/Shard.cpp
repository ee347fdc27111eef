#include "volume/Shard.h"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>

#include "common/Fnv1a64.h"

namespace baker {
namespace {

// x's low 21 bits spread to every third bit.
std::uint64_t spreadBits(std::uint64_t x) {
  x &= 0x1fffff;
  x = (x | x << 32) & 0x1f00000000ffffULL;
  x = (x | x << 16) & 0x1f0000ff0000ffULL;
  x = (x | x << 8) & 0x100f00f00f00f00fULL;
  x = (x | x << 4) & 0x10c30c30c30c30c3ULL;
  x = (x | x << 2) & 0x1249249249249249ULL;
  return x;
}

// Where shard `index` of `count` starts in the Morton order of `bricks` bricks.
std::int64_t shardStart(std::int64_t bricks, int index, int count) { return bricks * index / count; }

}  // namespace

std::string shardName(const Shard& shard) { return fmt::format("{}/{}", shard.index, shard.count); }

std::optional<Shard> parseShard(const std::string& text) {
  const std::size_t slash = text.find('/');
  if (slash == std::string::npos) return std::nullopt;
  Shard shard;
  const auto number = [](const char* first, const char* last, int& value) {
    const auto [end, error] = std::from_chars(first, last, value);
    return first != last && error == std::errc() && end == last;
  };
  if (!number(text.data(), text.data() + slash, shard.index) ||
      !number(text.data() + slash + 1, text.data() + text.size(), shard.count))
    return std::nullopt;
  if (shard.count < 1 || shard.count > kMaxShards || shard.index < 0 || shard.index >= shard.count) return std::nullopt;
  return shard;
}

namespace {

// `bricks` of `grid` in Morton order of their brick coordinates: an adaptive level's placed
// bricks alone, not the whole grid's, which a fine level may have far more of.
std::vector<std::int64_t> inMortonOrder(const ProbeGrid& grid, const std::vector<std::int64_t>& bricks) {
  std::vector<std::pair<std::uint64_t, std::int64_t>> keyed;
  keyed.reserve(bricks.size());
  for (const std::int64_t b : bricks) {
    const Eigen::Vector3i c = grid.brickCorner(b) / kBrickSize;
    keyed.push_back({spreadBits(std::uint64_t(c.x())) | spreadBits(std::uint64_t(c.y())) << 1 |
                         spreadBits(std::uint64_t(c.z())) << 2,
                     b});
  }
  // Codes are unique (brick coordinates are below 2^21), so the order is total.
  std::sort(keyed.begin(), keyed.end());
  std::vector<std::int64_t> order(keyed.size());
  std::transform(keyed.begin(), keyed.end(), order.begin(), [](const auto& k) { return k.second; });
  return order;
}

}  // namespace

std::vector<std::int64_t> bricksInMortonOrder(const ProbeGrid& grid) {
  std::vector<std::int64_t> all(std::size_t(grid.brickCount()));
  for (std::size_t b = 0; b < all.size(); ++b) all[b] = std::int64_t(b);
  return inMortonOrder(grid, all);
}

std::vector<std::int64_t> shardBricks(const ProbeGrid& grid, const Shard& shard) {
  const std::vector<std::int64_t> order = bricksInMortonOrder(grid);
  const std::int64_t n = std::int64_t(order.size());
  return {order.begin() + shardStart(n, shard.index, shard.count),
          order.begin() + shardStart(n, shard.index + 1, shard.count)};
}

std::vector<std::vector<std::vector<std::int64_t>>> everyShardsLevelBricks(
    const std::vector<ProbeGrid>& grids, const std::vector<std::vector<std::int64_t>>& placed, int count) {
  std::int64_t total = 0;
  for (const std::vector<std::int64_t>& bricks : placed) total += std::int64_t(bricks.size());
  std::vector<std::vector<std::vector<std::int64_t>>> shares(std::size_t(count),
                                                            std::vector<std::vector<std::int64_t>>(placed.size()));
  std::int64_t rank = 0;  // of the brick in the order over every level
  int shard = 0;
  for (std::size_t level = 0; level < placed.size(); ++level) {
    for (const std::int64_t b : inMortonOrder(grids[level], placed[level])) {
      while (rank >= shardStart(total, shard + 1, count)) ++shard;
      shares[std::size_t(shard)][level].push_back(b);
      ++rank;
    }
  }
  for (auto& share : shares)
    for (std::vector<std::int64_t>& bricks : share) std::sort(bricks.begin(), bricks.end());
  return shares;
}

std::vector<std::vector<std::int64_t>> shardLevelBricks(const std::vector<ProbeGrid>& grids,
                                                        const std::vector<std::vector<std::int64_t>>& placed,
                                                        const Shard& shard) {
  return everyShardsLevelBricks(grids, placed, shard.count)[std::size_t(shard.index)];
}

std::vector<std::int64_t> shardLevelBrickCounts(const std::vector<std::int64_t>& placedPerLevel, const Shard& shard) {
  std::int64_t total = 0;
  for (const std::int64_t n : placedPerLevel) total += n;
  const std::int64_t first = shardStart(total, shard.index, shard.count), end = shardStart(total, shard.index + 1, shard.count);
  std::vector<std::int64_t> counts;
  std::int64_t rank = 0;
  for (const std::int64_t n : placedPerLevel) {
    counts.push_back(std::max<std::int64_t>(0, std::min(end, rank + n) - std::max(first, rank)));
    rank += n;
  }
  return counts;
}

std::vector<int> shardOfBricks(const ProbeGrid& grid, int count) {
  const std::vector<std::int64_t> order = bricksInMortonOrder(grid);
  const std::int64_t n = std::int64_t(order.size());
  std::vector<int> shardOf(order.size(), 0);
  for (int s = 0; s < count; ++s)
    for (std::int64_t r = shardStart(n, s, count); r < shardStart(n, s + 1, count); ++r) shardOf[order[r]] = s;
  return shardOf;
}

std::vector<std::int64_t> probesOfBrick(const ProbeGrid& grid, std::int64_t brick) {
  const Eigen::Vector3i lo = grid.brickCorner(brick);
  const Eigen::Vector3i hi = lo + grid.brickExtent(brick);
  std::vector<std::int64_t> probes;
  probes.reserve(std::size_t(kBrickSize * kBrickSize * kBrickSize));
  for (int k = lo.z(); k < hi.z(); ++k)
    for (int j = lo.y(); j < hi.y(); ++j)
      for (int i = lo.x(); i < hi.x(); ++i) probes.push_back(grid.linearIndex(i, j, k));
  return probes;
}

std::string bakeFingerprint(const std::string& basisName, const ProbeGrid& grid,
                            const std::map<std::string, std::string>& settings) {
  Fnv1a64 hash;
  const auto text = [&](const std::string& s) {
    hash.add(s.data(), s.size());
    hash.add("\0", 1);  // "ab"+"c" and "a"+"bc" hash differently
  };
  text(basisName);
  text(fmt::format("{} {} {} {:.17g} {:.17g} {:.17g} {:.17g}", grid.dims.x(), grid.dims.y(), grid.dims.z(),
                   grid.origin.x(), grid.origin.y(), grid.origin.z(), grid.spacing));
  for (const auto& [key, value] : settings) {  // std::map: in key order
    text(key);
    text(value);
  }
  return fmt::format("{:016x}", hash.value());
}

}  // namespace baker
