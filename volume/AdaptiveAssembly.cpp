#include "volume/AdaptiveAssembly.h"

#include <fmt/format.h>

#include <algorithm>
#include <utility>

#include "basis/BasisRegistry.h"
#include "common/Error.h"
#include "volume/AdaptiveFinish.h"
#include "volume/LevelPacking.h"
#include "volume/MemoryEstimate.h"
#include "volume/StoredBricks.h"
#include "volume/VolumeAssembly.h"

namespace baker {
namespace {

InputError notAnAdaptivePart(const std::string& name) {
  return InputError(fmt::format("{}: not a shard's part of an adaptive bake (no baker.shard.placement); merge the "
                                "parts of one bake", name));
}

void requireSameLevels(const AdaptiveVolume& part, const std::string& name, const AdaptiveVolume& first,
                       const std::string& firstName) {
  const auto mismatch = [&](const std::string& field, const std::string& here, const std::string& there) {
    throw InputError(fmt::format("{}: {} is {}, but {} has {}: the parts are not of one bake", name, field, here,
                                 firstName, there));
  };
  if (!part.placement) throw notAnAdaptivePart(name);
  requireSameBake(part.levels.front(), name, first.levels.front(), firstName);
  if (part.levels.size() != first.levels.size())
    mismatch("baker.levels", std::to_string(part.levels.size()), std::to_string(first.levels.size()));
  if (part.marginCells != first.marginCells)
    mismatch("baker.margin_cells", std::to_string(part.marginCells), std::to_string(first.marginCells));
  for (std::size_t k = 1; k < part.levels.size(); ++k) {
    const ProbeGrid &g = part.levels[k].grid, &f = first.levels[k].grid;
    if (g.dims != f.dims || g.origin != f.origin || g.spacing != f.spacing)
      mismatch(fmt::format("level {}'s grid", k), "another", "a different one");
  }
  if (!(*part.placement == *first.placement))
    mismatch("baker.shard.placement", part.placement->fingerprint, first.placement->fingerprint);
  for (const Volume& level : part.levels)
    if (!level.shard || !(*level.shard == *part.levels.front().shard))
      throw InputError(fmt::format("{}: its levels are not all of shard {}", name, shardName(*part.levels.front().shard)));
}

}  // namespace

AdaptiveAssembly::AdaptiveAssembly(const AdaptiveVolume& first, const std::string& firstName)
    : firstName_(firstName) {
  if (!first.placement || first.levels.empty() || !first.levels.front().shard) throw notAnAdaptivePart(firstName);
  if (first.placement->bricksPerLevel.size() != first.levels.size())
    throw InputError(fmt::format("{}: baker.shard.placed_bricks lists {} levels, the file holds {}", firstName,
                                 first.placement->bricksPerLevel.size(), first.levels.size()));
  // The parts, then the whole volume: about volumeMemoryBytes (twice the values), checked before
  // any part beyond the first is read.
  double probes = 0.0;
  for (const std::int64_t bricks : first.placement->bricksPerLevel) probes += double(bricks) * kBrickSize * kBrickSize * kBrickSize;
  const std::unique_ptr<Basis> basis = makeBasis(first.coarsest().basisName);
  if (volumeMemoryBytes(probes, *basis) > double(physicalMemoryBytes()))
    throw InputError(fmt::format("{}: the bake places {} bricks (baker.shard.placed_bricks); putting them together "
                                 "would need about {:.3g} GiB, more than this machine has",
                                 firstName, bricksPerLevelText(first.placement->bricksPerLevel),
                                 volumeMemoryBytes(probes, *basis) / double(1ull << 30)));
  first_ = levelsWithoutValues(first);
  given_.assign(std::size_t(first.levels.front().shard->count), "");
}

void AdaptiveAssembly::add(AdaptiveVolume part, const std::string& name) {
  requireSameLevels(part, name, first_, firstName_);
  // Each part holds exactly its share's count per level, so that the parts together hold the
  // placement once, and no more than that is ever held.
  const Shard& shard = *part.levels.front().shard;
  const std::vector<std::int64_t> expected = shardLevelBrickCounts(first_.placement->bricksPerLevel, shard);
  for (std::size_t k = 0; k < part.levels.size(); ++k) {
    const std::size_t held = heldBricksInOrder(part.levels[k]).size();
    if (std::int64_t(held) != expected[k])
      throw InputError(fmt::format("{}: level {} holds {} bricks, but shard {}'s share of the placement "
                                   "(baker.shard.placed_bricks) is {}",
                                   name, k, held, shardName(shard), expected[k]));
  }
  claimShard(given_, shard, name);
  parts_.push_back(std::move(part));
  names_.push_back(name);
}

// Which part holds each brick of level `index`, by brick; InputError when two parts hold one.
std::vector<std::pair<std::int64_t, std::size_t>> AdaptiveAssembly::owners(int index) const {
  std::vector<std::pair<std::int64_t, std::size_t>> owners;  // (brick, part)
  for (std::size_t p = 0; p < parts_.size(); ++p)
    for (const std::int64_t b : heldBricksInOrder(parts_[p].levels[std::size_t(index)])) owners.push_back({b, p});
  std::sort(owners.begin(), owners.end());
  for (std::size_t n = 1; n < owners.size(); ++n)
    if (owners[n].first == owners[n - 1].first)
      throw InputError(fmt::format("{}: brick {} of level {} is also in {}; the parts are not one partition of the bake",
                                   names_[owners[n].second], owners[n].first, index, names_[owners[n - 1].second]));
  return owners;
}

// Level `index` of the whole bake from the parts' bricks of it (`owners`), which the parts then let go.
Volume AdaptiveAssembly::level(int index, const std::vector<std::pair<std::int64_t, std::size_t>>& owners) {
  const std::size_t k = std::size_t(index);
  const ProbeGrid& grid = first_.levels[k].grid;
  std::vector<std::int64_t> bricks;
  std::vector<std::uint8_t> masks;
  for (const auto& [brick, p] : owners) {
    bricks.push_back(brick);
    masks.push_back(parts_[p].levels[k].rows.subBricks(grid, brick));
  }
  Volume whole = first_.levels[k];
  whole.shard.reset();
  whole.rows = ProbeRows(grid, bricks, masks);
  if (std::int64_t(bricks.size()) == grid.brickCount() && !whole.rows.holdsPartialBricks()) whole.rows = ProbeRows();
  holdZeroProbes(whole);
  const auto into = whole.floatRows();
  for (const auto& [brick, p] : owners) {
    const Volume& part = parts_[p].levels[k];
    const auto from = part.floatRows();
    forEachHeldProbeOfBrick(grid, part.rows, brick, [&](int x, int y, int z, std::int64_t row) {
      const std::int64_t to = whole.rows.row(grid, x, y, z);
      whole.states[std::size_t(to)] = part.states[std::size_t(row)];
      whole.offsets[std::size_t(to)] = part.offsets[std::size_t(row)];
      for (std::size_t a = 0; a < into.size(); ++a) {
        const int w = into[a].width;
        std::copy_n(from[a].values->begin() + row * w, w, into[a].values->begin() + to * w);
      }
    });
  }
  requireBorderStates(whole, index, ProbeRows(grid, bricks, masks), owners);
  for (AdaptiveVolume& part : parts_) part.levels[k] = Volume();
  return whole;
}

// The parts' state 3 (Interpolated) must be the level's border exactly, as the placement decides
// it: the finish gives those probes, and only those, the coarser levels' values.
void AdaptiveAssembly::requireBorderStates(const Volume& level, int index, const ProbeRows& placed,
                                           const std::vector<std::pair<std::int64_t, std::size_t>>& owners) const {
  const ProbeGrid& grid = level.grid;
  for (const auto& owner : owners) {
    const std::string& part = names_[owner.second];  // a lambda may not capture a structured binding (C++17)
    forEachHeldProbeOfBrick(grid, level.rows, owner.first, [&](int x, int y, int z, std::int64_t row) {
      const bool interpolated = level.states[std::size_t(row)] == ProbeState::Interpolated;
      if (interpolated != (index > 0 && onLevelBorder(grid, placed, x, y, z)))
        throw InputError(fmt::format("{}: probe ({}, {}, {}) of level {} is {} but {} on the level's border: the "
                                     "part is damaged or of another placement",
                                     part, x, y, z, index, interpolated ? "interpolated" : "traced",
                                     interpolated ? "not" : "lies"));
    });
  }
}

AdaptiveVolume AdaptiveAssembly::finish() {
  requireEveryShard(given_);
  // The placement first, from the parts' brick lists alone: a brick outside it is named before
  // the levels are put together.
  std::vector<std::vector<std::pair<std::int64_t, std::size_t>>> owned;
  std::vector<std::vector<std::int64_t>> placed;
  std::vector<std::vector<std::uint8_t>> masks;
  for (int k = 0; k < int(first_.levels.size()); ++k) {
    owned.push_back(owners(k));
    placed.emplace_back();
    masks.emplace_back();
    for (const auto& [brick, p] : owned.back()) {
      placed.back().push_back(brick);
      masks.back().push_back(parts_[p].levels[std::size_t(k)].rows.subBricks(first_.levels[std::size_t(k)].grid, brick));
    }
  }
  const PlacementSummary together = summarizePlacement(placed, masks);
  if (!(together == *first_.placement))
    throw InputError(fmt::format("{} and the other parts: their bricks ({} per level, hash {}) are not the placement "
                                 "their files record ({}, hash {}): a part is damaged or of another bake",
                                 firstName_, bricksPerLevelText(together.bricksPerLevel), together.fingerprint,
                                 bricksPerLevelText(first_.placement->bricksPerLevel), first_.placement->fingerprint));
  AdaptiveVolume whole;
  whole.marginCells = first_.marginCells;
  for (int k = 0; k < int(first_.levels.size()); ++k) whole.levels.push_back(level(k, owned[std::size_t(k)]));
  parts_.clear();
  finishAdaptiveLevels(whole);
  return whole;
}

}  // namespace baker
