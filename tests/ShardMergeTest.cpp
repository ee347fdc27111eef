#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "bake/Baker.h"
#include "common/Error.h"
#include "basis/BasisRegistry.h"
#include "formats/VdbWriter.h"
#include "formats/VolumeReader.h"
#include "tests/BakerProcess.h"
#include "tests/TestData.h"
#include "tests/VolumeFiles.h"
#include "volume/ProbeRows.h"
#include "volume/Shard.h"

// A bake cut into shards, merged, must be the one-process bake byte for byte; the merge refuses
// parts that are not one bake, once each.
namespace baker {
namespace {

namespace fs = std::filesystem;
using test::bytesOf;
using test::expectSameFiles;
using test::runBaker;

// default_room at 0.3 m: 2 × 2 × 2 bricks, probes in its walls (relocated, and invalid ones
// filled from neighbours) on brick borders; a short fixed bake with every effect it has.
const std::vector<std::string> kBake = {"--spacing", "0.3", "--rays", "16", "--bounces", "1", "--basis", "ad-ycocg",
                                        "--quiet"};

std::string scenePath() { return test::sourcePath("data/default_room/default_room.gltf"); }

std::vector<std::string> bakeArgs(const std::vector<std::string>& extra) {
  std::vector<std::string> args = {scenePath()};
  args.insert(args.end(), kBake.begin(), kBake.end());
  args.insert(args.end(), extra.begin(), extra.end());
  return args;
}

// The shards' parts of `count`, baked one process each, named part-K.EXT.
std::vector<std::string> bakeParts(const std::string& dir, int count, const std::string& ext) {
  std::vector<std::string> parts;
  for (int k = 0; k < count; ++k) {
    parts.push_back(dir + "/part-" + std::to_string(k) + ext);
    const auto r = runBaker(dir, bakeArgs({"--shard", std::to_string(k) + "/" + std::to_string(count), "--out",
                                           parts.back()}));
    EXPECT_EQ(r.exitCode, 0) << r.err;
  }
  return parts;
}

class ShardedBake : public ::testing::TestWithParam<std::string> {};

TEST_P(ShardedBake, MergedPartsAreTheOneProcessBakeByteForByte) {
  const std::string ext = GetParam();
  const std::string dir = test::makeTempDir("shards" + ext);
  const std::string whole = dir + "/whole" + ext;
  const auto r = runBaker(dir, bakeArgs({"--out", whole}));
  ASSERT_EQ(r.exitCode, 0) << r.err;

  // The scene must exercise what crosses brick borders: a probe filled from a neighbour in
  // another shard, and relocated probes in bricks of both shards.
  const Volume volume = readVolume(whole);
  const std::vector<int> shardOf = shardOfBricks(volume.grid, 2);
  const auto brickOfProbe = [&](std::int64_t p) {
    const Eigen::Vector3i d = volume.grid.dims, b = volume.grid.brickCounts();
    const std::int64_t i = p % d.x(), j = p / d.x() % d.y(), k = p / (std::int64_t(d.x()) * d.y());
    return i / kBrickSize + b.x() * (j / kBrickSize + b.y() * (k / kBrickSize));
  };
  bool fillCrossesShards = false;
  int relocatedInShard[2] = {0, 0};
  for (std::int64_t p = 0; p < volume.grid.probeCount(); ++p) {
    if (volume.states[p] == ProbeState::Relocated) ++relocatedInShard[shardOf[brickOfProbe(p)]];
    if (volume.states[p] != ProbeState::Invalid) continue;
    for (const std::int64_t step : {std::int64_t(1), std::int64_t(volume.grid.dims.x()),
                                    std::int64_t(volume.grid.dims.x()) * volume.grid.dims.y()})
      for (const std::int64_t n : {p - step, p + step})
        if (n >= 0 && n < volume.grid.probeCount() && volume.states[n] != ProbeState::Invalid &&
            shardOf[brickOfProbe(n)] != shardOf[brickOfProbe(p)])
          fillCrossesShards = true;
  }
  ASSERT_TRUE(fillCrossesShards) << "no invalid probe is filled from a neighbour in the other shard";
  ASSERT_GT(relocatedInShard[0], 0);
  ASSERT_GT(relocatedInShard[1], 0);

  for (int count : {2, 3}) {
    std::vector<std::string> parts = bakeParts(dir, count, count == 2 ? ext : "-of-3" + ext);
    std::reverse(parts.begin(), parts.end());  // the order the parts are given in does not matter
    std::vector<std::string> args = {"merge", dir + "/merged-" + std::to_string(count) + ext};
    args.insert(args.end(), parts.begin(), parts.end());
    const auto m = runBaker(dir, args);
    ASSERT_EQ(m.exitCode, 0) << m.err;
    expectSameFiles(args[1], whole);
  }
}

INSTANTIATE_TEST_SUITE_P(Formats, ShardedBake, ::testing::Values(".vdb", "_exr"),
                         [](const auto& info) { return info.param == ".vdb" ? "vdb" : "exr"; });

TEST(Shards, PartsOfEveryBrickAreDisjointAndComplete) {
  ProbeGrid grid;
  grid.dims = {37, 9, 50};  // 5 × 2 × 7 bricks, partial on every axis
  std::vector<int> seen(std::size_t(5 * 2 * 7), 0);
  for (int k = 0; k < 9; ++k)
    for (const std::int64_t b : shardBricks(grid, {k, 9})) ++seen[std::size_t(b)];
  EXPECT_TRUE(std::all_of(seen.begin(), seen.end(), [](int n) { return n == 1; }));
  EXPECT_TRUE(shardBricks(grid, {0, 4096}).empty()) << "more shards than bricks: some hold none";
  EXPECT_EQ(parseShard("3/8")->index, 3);
  for (const char* bad : {"8/8", "-1/2", "1/0", "1/4097", "1/2/3", "a/b", "1/", "/2", " 1/2", "1/2 "})
    EXPECT_FALSE(parseShard(bad)) << bad;
}

// A part's rows are its bricks' probes, each in exactly one row, brick after brick.
TEST(Shards, APartHoldsARowForEachProbeOfItsBricksAndNoOther) {
  ProbeGrid grid;
  grid.dims = {37, 9, 50};
  const std::vector<std::int64_t> bricks = shardBricks(grid, {4, 9});
  const ProbeRows rows(grid, bricks);
  std::vector<int> hits(std::size_t(rows.count(grid)), 0);
  std::vector<bool> held(std::size_t(grid.probeCount()), false);
  std::int64_t next = 0;
  for (const std::int64_t b : bricks)
    for (const std::int64_t p : probesOfBrick(grid, b)) {
      EXPECT_EQ(rows.row(grid, p), next++) << "probe " << p << " of brick " << b;
      held[std::size_t(p)] = true;
    }
  EXPECT_EQ(next, rows.count(grid));
  for (std::int64_t p = 0; p < grid.probeCount(); ++p)
    if (!held[std::size_t(p)]) ASSERT_EQ(rows.row(grid, p), -1) << "probe " << p;
  EXPECT_EQ(ProbeRows().row(grid, 123), 123) << "a whole volume: probe p in row p";
}

// A shard's bake allocates its own bricks' probes, not the grid's: what bounds each machine's
// memory by its share of the work.
TEST(Shards, AShardsBakeHoldsOnlyItsBricks) {
  const Scene scene;
  const RayTracer tracer(scene);
  const auto basis = makeBasis("ad-ycocg");
  ProbeGrid grid;
  grid.dims = {24, 16, 8};  // 3 × 2 × 1 bricks
  BakeSettings settings;
  settings.rays = 4;
  BakeStats stats;
  const Volume part = bakeVolume(scene, tracer, *basis, grid, settings, &stats, {}, Shard{1, 3});
  EXPECT_EQ(stats.probes, 2 * 512);
  EXPECT_EQ(part.states.size(), std::size_t(2 * 512));
  EXPECT_EQ(part.coefficients.size(), std::size_t(2 * 512 * part.coefficientsPerProbe));
  for (const std::int64_t b : shardBricks(grid, {1, 3}))
    for (const std::int64_t p : probesOfBrick(grid, b)) ASSERT_EQ(part.states[part.rowOf(p)], ProbeState::Valid);
}

// The merge reads a part as its own bricks only (the whole volume and one share in memory, not
// two whole volumes): the same values, and a probe of another shard's brick is refused.
TEST(Shards, APartReadAsItsOwnBricksHoldsItsValuesAndRefusesAnotherShardsProbe) {
  const Scene scene;
  const RayTracer tracer(scene);
  const auto basis = makeBasis("sh-l1");
  ProbeGrid grid;
  grid.dims = {20, 9, 8};  // 3 × 2 × 1 bricks, partial on x and y
  BakeSettings settings;
  settings.rays = 4;
  const Volume part = bakeVolume(scene, tracer, *basis, grid, settings, nullptr, {}, Shard{0, 2});
  const std::string dir = test::makeTempDir("own_bricks");
  writeVdb(part, *basis, dir + "/part.vdb");
  const Volume back = readVolume(dir + "/part.vdb", PartReading::OwnBricks);
  ASSERT_EQ(back.rows.count(grid), part.rows.count(grid));
  for (const std::int64_t b : shardBricks(grid, {0, 2}))
    for (const std::int64_t p : probesOfBrick(grid, b))
      for (int c = 0; c < part.coefficientsPerProbe; ++c)
        ASSERT_EQ(back.probe(p)[c], part.probe(p)[c]) << "probe " << p;

  Volume stray = readVolume(dir + "/part.vdb");  // every probe: zeros outside its bricks
  const std::int64_t other = probesOfBrick(grid, shardBricks(grid, {1, 2}).front()).front();
  stray.states[std::size_t(other)] = ProbeState::Valid;
  writeVdb(stray, *basis, dir + "/stray.vdb");
  try {
    readVolume(dir + "/stray.vdb", PartReading::OwnBricks);
    ADD_FAILURE() << "read";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(fmt::format("holds probe {}, outside the bricks of its shard 0/2", other)),
              std::string::npos)
        << e.what();
  }
}

// More shards than bricks: a shard without a brick still writes a part, and the merge takes it.
TEST(Shards, AShardWithoutBricksIsMerged) {
  const std::string dir = test::makeTempDir("shard_without_bricks");
  const std::vector<std::string> oneBrick = {scenePath(), "--spacing", "1", "--rays", "16", "--bounces", "0", "--quiet"};
  const auto bake = [&](std::vector<std::string> extra) {
    std::vector<std::string> args = oneBrick;
    args.insert(args.end(), extra.begin(), extra.end());
    const auto r = runBaker(dir, args);
    EXPECT_EQ(r.exitCode, 0) << r.err;
  };
  bake({"--out", "whole.vdb"});
  bake({"--shard", "0/2", "--out", "part0.vdb"});
  bake({"--shard", "1/2", "--out", "part1.vdb"});
  ASSERT_EQ(readVolume(dir + "/part0.vdb", PartReading::OwnBricks).states.size(), 0u);
  const auto m = runBaker(dir, {"merge", "merged.vdb", "part0.vdb", "part1.vdb"});
  ASSERT_EQ(m.exitCode, 0) << m.err;
  EXPECT_EQ(bytesOf(dir + "/merged.vdb"), bytesOf(dir + "/whole.vdb"));
}

class MergeRefuses : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = test::makeTempDir("merge_refuses");
    parts_ = bakeParts(dir_, 2, ".vdb");
  }
  // Runs the merge into `out` and expects exit 2 with `message` on stderr and no output.
  static void expectRefused(const std::vector<std::string>& parts, const std::string& message) {
    const std::string out = dir_ + "/merged.vdb";
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
std::string MergeRefuses::dir_;
std::vector<std::string> MergeRefuses::parts_;

TEST_F(MergeRefuses, AMissingShard) { expectRefused({parts_[1]}, "shard 0/2 missing"); }

TEST_F(MergeRefuses, AShardGivenTwice) {
  fs::copy_file(parts_[0], dir_ + "/copy.vdb", fs::copy_options::overwrite_existing);
  expectRefused({parts_[0], parts_[1], dir_ + "/copy.vdb"}, "shard 0/2 is given twice");
}

TEST_F(MergeRefuses, APartFromAnotherSetting) {
  const std::string other = dir_ + "/seed1.vdb";
  const auto r = runBaker(dir_, bakeArgs({"--shard", "1/2", "--seed", "1", "--out", other}));
  ASSERT_EQ(r.exitCode, 0) << r.err;
  expectRefused({parts_[0], other}, other + ": baker.setting.seed is \"1\", but " + parts_[0] + " has \"0\"");
}

// Radiance and irradiance coefficients do not go into one grid (64 rays: a radiance fit needs
// more rays than the basis has functions).
TEST_F(MergeRefuses, APartOfAnotherSignal) {
  std::string parts[2];
  for (int k = 0; k < 2; ++k) {
    parts[k] = dir_ + (k == 0 ? "/irradiance-0.vdb" : "/radiance-1.vdb");
    const auto r = runBaker(dir_, {scenePath(), "--spacing", "0.3", "--rays", "64", "--bounces", "0", "--basis", "sh-l2",
                                   "--signal", k == 0 ? "irradiance" : "radiance", "--shard", fmt::format("{}/2", k),
                                   "--out", parts[k], "--quiet"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
  }
  expectRefused({parts[0], parts[1]}, parts[1] + ": baker.setting.signal is \"radiance\", but " + parts[0] + " has \"irradiance\"");
}

TEST_F(MergeRefuses, APartFromAnotherScene) {
  // The same room with one vertex moved: the same grid, another scene.
  const std::string scene = dir_ + "/moved_room.gltf";
  std::string gltf = bytesOf(scenePath());
  fs::copy_file(test::sourcePath("data/default_room/default_room.bin"), dir_ + "/default_room.bin",
                fs::copy_options::overwrite_existing);
  gltf += " ";  // the scene's hash is over its bytes: any change is another scene
  std::ofstream(scene, std::ios::binary) << gltf;
  const std::string other = dir_ + "/moved.vdb";
  std::vector<std::string> args = bakeArgs({"--shard", "1/2", "--out", other});
  args[0] = scene;
  const auto r = runBaker(dir_, args);
  ASSERT_EQ(r.exitCode, 0) << r.err;
  expectRefused({parts_[0], other}, other + ": baked from another scene");
}

TEST_F(MergeRefuses, APartOfAnotherShardCount) {
  const std::string other = dir_ + "/third.vdb";
  const auto r = runBaker(dir_, bakeArgs({"--shard", "1/3", "--out", other}));
  ASSERT_EQ(r.exitCode, 0) << r.err;
  expectRefused({parts_[0], other}, other + ": baker.shard is 1/3");
}

TEST_F(MergeRefuses, ATruncatedPart) {
  const std::string cut = dir_ + "/cut.vdb";
  const std::string bytes = bytesOf(parts_[1]);
  std::ofstream(cut, std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  expectRefused({parts_[0], cut}, cut);
}

TEST_F(MergeRefuses, AVolumeThatIsNotAPart) {
  const std::string whole = dir_ + "/whole.vdb";
  const auto r = runBaker(dir_, bakeArgs({"--out", whole}));
  ASSERT_EQ(r.exitCode, 0) << r.err;
  expectRefused({whole, parts_[1]}, whole + ": not a shard's part");
}

TEST(Shards, BadShardFlagsAreRefused) {
  const std::string dir = test::makeTempDir("bad_shards");
  for (const char* bad : {"2/2", "a/b", "0/5000", "1"}) {
    const auto r = runBaker(dir, bakeArgs({"--shard", bad}));
    EXPECT_EQ(r.exitCode, 2) << bad;
    EXPECT_NE(r.err.find("--shard " + std::string(bad)), std::string::npos) << r.err;
  }
  const auto engine = runBaker(dir, bakeArgs({"--shard", "0/2", "--format", "bevy"}));
  EXPECT_EQ(engine.exitCode, 2);
  EXPECT_NE(engine.err.find("baker merge --format bevy"), std::string::npos) << engine.err;
  EXPECT_TRUE(fs::is_empty(dir));
}

#ifdef BAKER_MPIEXEC
// mpirun refuses to start as root unless told twice; CI containers run as root.
const std::string kMpirun = std::string("OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 '") +
                            BAKER_MPIEXEC + "' --oversubscribe -np 2";
#endif

TEST(Mpi, TwoRanksWriteTheOneProcessBake) {
#ifndef BAKER_MPIEXEC
  GTEST_SKIP() << "Open MPI was not found when this build was configured: skipping the mpirun check";
#else
  const std::string dir = test::makeTempDir("mpi");
  const auto one = runBaker(dir, bakeArgs({"--out", dir + "/whole.vdb"}));
  ASSERT_EQ(one.exitCode, 0) << one.err;
  const auto r = test::runBakerUnder(dir, kMpirun, test::shellWords(bakeArgs({"--mpi", "--json", "--out", dir + "/mpi.vdb"})));
  ASSERT_EQ(r.exitCode, 0) << r.err;
  expectSameFiles(dir + "/mpi.vdb", dir + "/whole.vdb");
  const nlohmann::json report = nlohmann::json::parse(r.out);
  EXPECT_EQ(report["ranks"], 2);
  ASSERT_EQ(report["per_rank"].size(), 2u);
  EXPECT_EQ(report["per_rank"][0]["probes"].get<std::int64_t>() + report["per_rank"][1]["probes"].get<std::int64_t>(),
            report["probes"].get<std::int64_t>());
  EXPECT_EQ(report["per_rank"][0]["threads"], 1) << "two ranks on two cores: one thread each";
#endif
}

TEST(Mpi, AFailingRankStopsTheJobAndLeavesNothing) {
#ifndef BAKER_MPIEXEC
  GTEST_SKIP() << "Open MPI was not found when this build was configured: skipping the mpirun check";
#else
  const std::string dir = test::makeTempDir("mpi_fails");
  std::ofstream(dir + "/broken.gltf") << "{\"asset\": {\"version\": \"2.0\"}, \"scene\": 0, \"scenes\": [{\"nodes\": [0]}], \"nodes\": [{\"mesh\": 7}]}";
  const auto r = test::runBakerUnder(dir, kMpirun, test::shellWords({dir + "/broken.gltf", "--mpi", "--out", dir + "/out.vdb"}));
  EXPECT_NE(r.exitCode, 0);
  EXPECT_NE(r.err.find("baker (rank "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("broken.gltf"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir + "/out.vdb"));
#endif
}

}  // namespace
}  // namespace baker
