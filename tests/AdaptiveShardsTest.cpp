#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "formats/VdbWriter.h"
#include "formats/VolumeReader.h"
#include "tests/BakerProcess.h"
#include "tests/TestData.h"
#include "tests/VolumeFiles.h"
#include "volume/AdaptiveFinish.h"
#include "volume/Shard.h"
#include "volume/StoredBricks.h"
#include "volume/VolumeAssembly.h"

// An adaptive bake cut into shards (or run over MPI ranks), put together, must be the
// one-process bake byte for byte; the merge refuses parts that are not one bake, once each.
namespace baker {
namespace {

namespace fs = std::filesystem;
using test::expectSameFiles;
using test::runBaker;

// default_room at 0.15 m, three levels: 48 placed bricks, so every shard count below holds
// parts of a level whose coarser bricks another shard traced (border probes), and Invalid probes
// whose neighbours another shard traced (fill).
const std::vector<std::string> kBake = {"--placement", "adaptive", "--spacing", "0.15", "--rays", "16",
                                        "--bounces", "1", "--basis", "ad-ycocg", "--quiet"};

std::vector<std::string> bakeArgs(const std::vector<std::string>& extra) {
  std::vector<std::string> args = {test::sourcePath("data/default_room/default_room.gltf")};
  args.insert(args.end(), kBake.begin(), kBake.end());
  args.insert(args.end(), extra.begin(), extra.end());
  return args;
}

std::vector<std::string> bakeParts(const std::string& dir, int count) {
  std::vector<std::string> parts;
  for (int k = 0; k < count; ++k) {
    parts.push_back(fmt::format("{}/part-{}-of-{}.vdb", dir, k, count));
    const auto r = runBaker(dir, bakeArgs({"--shard", fmt::format("{}/{}", k, count), "--out", parts.back()}));
    EXPECT_EQ(r.exitCode, 0) << r.err;
  }
  return parts;
}

TEST(AdaptiveShardLevels, EveryPlacedBrickInExactlyOneShard) {
  std::vector<ProbeGrid> grids(2);
  grids[0].dims = Eigen::Vector3i(17, 9, 9);
  grids[0].spacing = 3.0;
  grids[1].dims = Eigen::Vector3i(49, 25, 25);
  std::vector<std::vector<std::int64_t>> placed(2);
  for (std::int64_t b = 0; b < grids[0].brickCount(); ++b) placed[0].push_back(b);
  for (std::int64_t b = 0; b < grids[1].brickCount(); b += 3) placed[1].push_back(b);
  for (int count : {1, 2, 5, 13, 40}) {
    std::vector<std::vector<std::int64_t>> together(2);
    std::size_t largest = 0, smallest = 1u << 30;
    for (int k = 0; k < count; ++k) {
      const auto share = shardLevelBricks(grids, placed, {k, count});
      std::size_t size = 0;
      for (std::size_t level = 0; level < 2; ++level) {
        EXPECT_TRUE(std::is_sorted(share[level].begin(), share[level].end()));
        together[level].insert(together[level].end(), share[level].begin(), share[level].end());
        size += share[level].size();
      }
      largest = std::max(largest, size);
      smallest = std::min(smallest, size);
    }
    for (std::size_t level = 0; level < 2; ++level) {
      std::sort(together[level].begin(), together[level].end());
      EXPECT_EQ(together[level], placed[level]) << count << " shards, level " << level;
    }
    EXPECT_LE(largest - smallest, 1u) << count << " shards: as even as whole bricks allow";
  }
  // What the merge expects of each part, from the counts alone.
  const std::vector<std::int64_t> perLevel = {std::int64_t(placed[0].size()), std::int64_t(placed[1].size())};
  for (int count = 1; count <= 60; ++count) {
    const auto shares = everyShardsLevelBricks(grids, placed, count);
    for (int k = 0; k < count; ++k) {
      const std::vector<std::int64_t> counts = shardLevelBrickCounts(perLevel, {k, count});
      for (std::size_t level = 0; level < 2; ++level)
        EXPECT_EQ(counts[level], std::int64_t(shares[std::size_t(k)][level].size())) << k << "/" << count;
    }
  }
}

TEST(AdaptiveShardLevels, BorderProbesDependOnThePlacementNotTheShare) {
  ProbeGrid grid;
  grid.dims = Eigen::Vector3i(24, 8, 8);  // bricks 0, 1, 2 along x
  const ProbeRows placed(grid, {0, 1});
  Volume whole, share;
  for (Volume* v : {&whole, &share}) v->grid = grid;
  share.rows = ProbeRows(grid, {0});
  whole.rows = ProbeRows(grid, {0, 1});
  whole.states.assign(std::size_t(whole.rows.count(grid)), ProbeState::Valid);
  share.states.assign(std::size_t(share.rows.count(grid)), ProbeState::Valid);
  markLevelBorder(whole, placed);
  markLevelBorder(share, placed);
  for (int k = 0; k < 8; ++k)
    for (int j = 0; j < 8; ++j)
      for (int i = 0; i < 8; ++i) {
        const ProbeState s = share.states[std::size_t(share.rows.row(grid, i, j, k))];
        EXPECT_EQ(s, whole.states[std::size_t(whole.rows.row(grid, i, j, k))]);
        // Brick 0's neighbour along x is placed: no border there, though the share lacks it.
        EXPECT_EQ(s, ProbeState::Valid) << i << " " << j << " " << k;
      }
  for (int i = 8; i < 16; ++i)
    EXPECT_EQ(whole.states[std::size_t(whole.rows.row(grid, i, 3, 3))],
              i == 15 ? ProbeState::Interpolated : ProbeState::Valid);
}

// `part` with level k's brick `drop` replaced by `add`, its values from `source` where it holds
// them (zeros and Invalid otherwise): the same count of bricks, another set.
AdaptiveVolume withBrickSwapped(const AdaptiveVolume& part, std::size_t k, std::int64_t drop, std::int64_t add,
                                const Volume& source) {
  AdaptiveVolume out = part;
  const Volume& from = part.levels[k];
  const ProbeGrid& grid = from.grid;
  std::vector<std::int64_t> bricks = heldBricksInOrder(from);
  *std::find(bricks.begin(), bricks.end(), drop) = add;
  std::sort(bricks.begin(), bricks.end());
  std::vector<std::uint8_t> masks;
  for (const std::int64_t b : bricks) {
    const Volume& values = b == add ? source : from;
    masks.push_back(values.rows.holdsBrick(b) ? values.rows.subBricks(grid, b) : subBricksInGrid(grid, b));
  }
  Volume level = volumeWithoutValues(from);
  level.rows = ProbeRows(grid, bricks, masks);
  holdZeroProbes(level);
  for (const std::int64_t b : bricks) {
    const Volume& values = b == add ? source : from;
    if (!values.rows.holdsBrick(b)) continue;
    forEachHeldProbeOfBrick(grid, values.rows, b, [&](int i, int j, int l, std::int64_t at) {
      const std::int64_t to = level.rows.row(grid, i, j, l);
      level.states[std::size_t(to)] = values.states[std::size_t(at)];
      std::copy_n(values.coefficients.begin() + at * level.coefficientsPerProbe, level.coefficientsPerProbe,
                  level.coefficients.begin() + to * level.coefficientsPerProbe);
    });
  }
  out.levels[k] = std::move(level);
  return out;
}

class AdaptiveShards : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = test::makeTempDir("adaptive_shards");
    const auto r = runBaker(dir_, bakeArgs({"--out", dir_ + "/whole.vdb"}));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    parts_ = bakeParts(dir_, 3);
  }
  // Runs the merge into `out` and expects exit 2 with `message` on stderr and no output.
  static void expectRefused(const std::vector<std::string>& parts, const std::string& message) {
    const std::string out = dir_ + "/refused.vdb";
    std::vector<std::string> args = {"merge", out};
    args.insert(args.end(), parts.begin(), parts.end());
    const auto r = runBaker(dir_, args);
    EXPECT_EQ(r.exitCode, 2) << r.err;
    EXPECT_NE(r.err.find(message), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out));
  }
  static std::string dir_;
  static std::vector<std::string> parts_;
};
std::string AdaptiveShards::dir_;
std::vector<std::string> AdaptiveShards::parts_;

TEST_F(AdaptiveShards, MergedPartsAreTheOneProcessBakeByteForByte) {
  // The levels really are cut: some level's bricks lie in more than one part.
  std::map<int, int> partsHoldingLevel;
  for (const std::string& part : parts_) {
    const AdaptiveVolume levels = readLevels(part);
    ASSERT_TRUE(levels.placement.has_value()) << part;
    for (std::size_t k = 0; k < levels.levels.size(); ++k) partsHoldingLevel[int(k)] += !levels.levels[k].states.empty();
  }
  EXPECT_GE(std::max_element(partsHoldingLevel.begin(), partsHoldingLevel.end(),
                             [](const auto& a, const auto& b) { return a.second < b.second; })->second, 2);
  // And some bricks hold only some of their sub-bricks, which the parts must carry over.
  const AdaptiveVolume whole = readLevels(dir_ + "/whole.vdb");
  EXPECT_TRUE(std::any_of(whole.levels.begin(), whole.levels.end(),
                          [](const Volume& level) { return level.rows.holdsPartialBricks(); }));

  for (int count : {1, 3, 7}) {
    std::vector<std::string> parts = count == 3 ? parts_ : bakeParts(dir_, count);
    std::reverse(parts.begin(), parts.end());  // the order the parts are given in does not matter
    std::vector<std::string> args = {"merge", fmt::format("{}/merged-{}.vdb", dir_, count), "--json"};
    args.insert(args.end(), parts.begin(), parts.end());
    const auto m = runBaker(dir_, args);
    ASSERT_EQ(m.exitCode, 0) << m.err;
    expectSameFiles(args[1], dir_ + "/whole.vdb");
    EXPECT_EQ(nlohmann::json::parse(m.out)["levels"], 3);
  }
  // EXR slices from the same parts: what the one-process bake writes as EXR.
  const auto exr = runBaker(dir_, bakeArgs({"--out", dir_ + "/whole_exr", "--format", "exr"}));
  ASSERT_EQ(exr.exitCode, 0) << exr.err;
  std::vector<std::string> args = {"merge", dir_ + "/merged_exr", "--format", "exr"};
  args.insert(args.end(), parts_.begin(), parts_.end());
  const auto m = runBaker(dir_, args);
  ASSERT_EQ(m.exitCode, 0) << m.err;
  expectSameFiles(dir_ + "/merged_exr", dir_ + "/whole_exr");
}

TEST(AdaptiveShardsBeyondBricks, EmptyPartsStillMerge) {
  // Two levels at 0.3 m: fewer placed bricks than shards, so some parts hold none at all.
  const std::string dir = test::makeTempDir("adaptive_empty_parts");
  const auto coarse = [](const std::vector<std::string>& extra) {
    std::vector<std::string> args = bakeArgs(extra);
    *std::find(args.begin(), args.end(), "0.15") = "0.3";
    args.insert(args.end(), {"--levels", "2", "--json"});
    return args;
  };
  const auto whole = runBaker(dir, coarse({"--out", dir + "/whole.vdb"}));
  ASSERT_EQ(whole.exitCode, 0) << whole.err;
  constexpr int kParts = 12;
  std::vector<std::string> args = {"merge", dir + "/merged.vdb"};
  int empty = 0;
  for (int k = 0; k < kParts; ++k) {
    args.push_back(fmt::format("{}/part-{}.vdb", dir, k));
    const auto r = runBaker(dir, coarse({"--shard", fmt::format("{}/{}", k, kParts), "--out", args.back()}));
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const nlohmann::json shard = nlohmann::json::parse(r.out)["shard"];
    ASSERT_LT(shard["bricks_in_grid"].get<int>(), kParts) << "the bake must place fewer bricks than there are parts";
    empty += shard["bricks"] == 0;
  }
  EXPECT_GT(empty, 0);
  const auto m = runBaker(dir, args);
  ASSERT_EQ(m.exitCode, 0) << m.err;
  expectSameFiles(dir + "/merged.vdb", dir + "/whole.vdb");
}

TEST_F(AdaptiveShards, MergeRefusesPartsThatAreNotOneBake) {
  expectRefused({parts_[0], parts_[2]}, "shard 1/3 missing");
  expectRefused({parts_[0], parts_[1], parts_[2], parts_[1]}, "shard 1/3 is given twice");
  const std::string seed = dir_ + "/seed1.vdb";
  ASSERT_EQ(runBaker(dir_, bakeArgs({"--shard", "1/3", "--seed", "1", "--out", seed})).exitCode, 0);
  expectRefused({parts_[0], seed, parts_[2]}, seed + ": baker.setting.seed is \"1\"");
  const std::string margin = dir_ + "/margin2.vdb";
  ASSERT_EQ(runBaker(dir_, bakeArgs({"--shard", "1/3", "--margin", "2", "--out", margin})).exitCode, 0);
  expectRefused({parts_[0], margin, parts_[2]}, margin + ": baker.setting.margin_cells is \"2\"");
  // A uniform bake's part among them, and an adaptive part among a uniform bake's.
  const std::string uniform = dir_ + "/uniform.vdb";
  std::vector<std::string> uniformArgs = bakeArgs({"--shard", "1/3", "--out", uniform});
  uniformArgs.erase(uniformArgs.begin() + 1, uniformArgs.begin() + 3);  // --placement adaptive
  ASSERT_EQ(runBaker(dir_, uniformArgs).exitCode, 0);
  expectRefused({parts_[0], uniform, parts_[2]}, uniform + ": a uniform volume, but " + parts_[0]);
  expectRefused({uniform, parts_[0]}, parts_[0] + ": an adaptive volume, but " + uniform);
  // The one-process volume is not a part.
  expectRefused({dir_ + "/whole.vdb", parts_[1]}, "whole.vdb: not a shard's part");
}

TEST_F(AdaptiveShards, MergeRefusesADamagedPart) {
  // A traced probe of a finer level marked interpolated: the merge would give it coarser values.
  AdaptiveVolume part = readLevels(parts_[2]);
  const std::unique_ptr<Basis> basis = basisOf(part.coarsest());
  const auto marked = [&](ProbeState from, ProbeState to, const std::string& name) {
    AdaptiveVolume damaged = part;
    for (std::size_t k = 1; k < damaged.levels.size(); ++k) {
      auto& states = damaged.levels[k].states;
      const auto at = std::find(states.begin(), states.end(), from);
      if (at == states.end()) continue;
      *at = to;
      writeAdaptiveVdb(damaged, *basis, dir_ + "/" + name);
      return true;
    }
    return false;
  };
  ASSERT_TRUE(marked(ProbeState::Valid, ProbeState::Interpolated, "traced.vdb"));
  expectRefused({parts_[0], parts_[1], dir_ + "/traced.vdb"}, "traced.vdb: probe (");
  ASSERT_TRUE(marked(ProbeState::Interpolated, ProbeState::Valid, "border.vdb"));
  expectRefused({parts_[0], parts_[1], dir_ + "/border.vdb"}, "lies on the level's border");
  // A brick dropped from a level: the share no longer matches the placement.
  AdaptiveVolume fewer = part;
  for (std::size_t k = fewer.levels.size(); k-- > 0;) {
    const std::vector<std::int64_t> held = heldBricksInOrder(fewer.levels[k]);
    if (held.empty()) continue;
    std::vector<bool> keep(std::size_t(fewer.levels[k].grid.brickCount()), false);
    for (std::size_t n = 1; n < held.size(); ++n) keep[std::size_t(held[n])] = true;
    fewer.levels[k] = keepBricks(std::move(fewer.levels[k]), keep);
    break;
  }
  writeAdaptiveVdb(fewer, *basis, dir_ + "/fewer.vdb");
  expectRefused({parts_[0], parts_[1], dir_ + "/fewer.vdb"}, "fewer.vdb: level ");

  // The right counts, but a brick swapped: for another part's, then for one the bake never placed.
  const AdaptiveVolume other = readLevels(parts_[1]);
  const std::size_t k = part.levels.size() - 1;
  const std::vector<std::int64_t> mine = heldBricksInOrder(part.levels[k]), theirs = heldBricksInOrder(other.levels[k]);
  ASSERT_FALSE(mine.empty());
  ASSERT_FALSE(theirs.empty());
  writeAdaptiveVdb(withBrickSwapped(part, k, mine.front(), theirs.front(), other.levels[k]), *basis,
                   dir_ + "/doubled.vdb");
  expectRefused({parts_[0], parts_[1], dir_ + "/doubled.vdb"}, "is also in");
  std::vector<std::int64_t> placed;
  for (const std::string& p : parts_)
    for (const std::int64_t b : heldBricksInOrder(readLevels(p).levels[k])) placed.push_back(b);
  std::sort(placed.begin(), placed.end());
  std::int64_t unplaced = 0;
  while (std::binary_search(placed.begin(), placed.end(), unplaced)) ++unplaced;
  ASSERT_LT(unplaced, part.levels[k].grid.brickCount());
  writeAdaptiveVdb(withBrickSwapped(part, k, mine.front(), unplaced, other.levels[k]), *basis, dir_ + "/stray.vdb");
  expectRefused({parts_[0], parts_[1], dir_ + "/stray.vdb"}, "are not the placement their files record");
}

TEST(AdaptiveMpi, TwoRanksWriteTheOneProcessBake) {
#ifndef BAKER_MPIEXEC
  GTEST_SKIP() << "Open MPI was not found when this build was configured: skipping the mpirun check";
#else
  const std::string dir = test::makeTempDir("adaptive_mpi");
  const auto one = runBaker(dir, bakeArgs({"--out", dir + "/whole.vdb"}));
  ASSERT_EQ(one.exitCode, 0) << one.err;
  const std::string mpirun = std::string("OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 '") +
                             BAKER_MPIEXEC + "' --oversubscribe -np 2";
  const auto r = test::runBakerUnder(dir, mpirun, test::shellWords(bakeArgs({"--mpi", "--json", "--out", dir + "/mpi.vdb"})));
  ASSERT_EQ(r.exitCode, 0) << r.err;
  expectSameFiles(dir + "/mpi.vdb", dir + "/whole.vdb");
  EXPECT_EQ(nlohmann::json::parse(r.out)["ranks"], 2);
#endif
}

}  // namespace
}  // namespace baker
