#include "volume/PlacementSummary.h"

#include <fmt/format.h>

#include <charconv>
#include <stdexcept>

#include "common/Fnv1a64.h"

namespace baker {

PlacementSummary summarizePlacement(const std::vector<std::vector<std::int64_t>>& bricks,
                                    const std::vector<std::vector<std::uint8_t>>& masks) {
  if (masks.size() != bricks.size()) throw std::logic_error("summarizePlacement: masks per level");
  PlacementSummary summary;
  Fnv1a64 hash;
  // Little-endian whatever the machine, so that parts baked on different machines agree.
  const auto add = [&](std::int64_t value) {
    char bytes[8];
    for (int i = 0; i < 8; ++i) bytes[i] = char(std::uint64_t(value) >> (8 * i) & 0xff);
    hash.add(bytes, 8);
  };
  for (std::size_t k = 0; k < bricks.size(); ++k) {
    const std::vector<std::int64_t>& level = bricks[k];
    if (masks[k].size() != level.size()) throw std::logic_error("summarizePlacement: a mask per brick");
    summary.bricksPerLevel.push_back(std::int64_t(level.size()));
    // The count first, so that where one level ends and the next begins is part of the hash.
    add(std::int64_t(level.size()));
    for (std::size_t n = 0; n < level.size(); ++n) {
      add(level[n]);
      add(masks[k][n]);
    }
  }
  summary.fingerprint = fmt::format("{:016x}", hash.value());
  return summary;
}

std::string bricksPerLevelText(const std::vector<std::int64_t>& counts) { return fmt::format("{}", fmt::join(counts, ",")); }

bool parseBricksPerLevel(const std::string& text, std::vector<std::int64_t>& counts) {
  counts.clear();
  const char* at = text.data();
  const char* end = text.data() + text.size();
  while (true) {
    std::int64_t n = 0;
    const auto [next, error] = std::from_chars(at, end, n);
    if (error != std::errc() || next == at || n < 0) return false;
    counts.push_back(n);
    if (next == end) return true;
    if (*next != ',') return false;
    at = next + 1;
  }
}

}  // namespace baker
