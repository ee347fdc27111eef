#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace baker {

// What a shard's part of an adaptive bake records of the whole bake's placement, which the parts'
// bricks together must make up: the bricks placed per level, and a hash over every level's.
struct PlacementSummary {
  std::vector<std::int64_t> bricksPerLevel;
  std::string fingerprint;  // 16 hex digits of FNV-1a over the levels' brick indices and sub-brick masks

  bool operator==(const PlacementSummary& other) const {
    return bricksPerLevel == other.bricksPerLevel && fingerprint == other.fingerprint;
  }
};

// `bricks`: per level, the bricks placed by increasing index; `masks`: each one's sub-bricks placed
// (volume/SubBricks.h).
PlacementSummary summarizePlacement(const std::vector<std::vector<std::int64_t>>& bricks,
                                    const std::vector<std::vector<std::uint8_t>>& masks);

// "n0,n1,…" and back; the parse gives none unless every count is a whole number ≥ 0.
std::string bricksPerLevelText(const std::vector<std::int64_t>& counts);
bool parseBricksPerLevel(const std::string& text, std::vector<std::int64_t>& counts);

}  // namespace baker
