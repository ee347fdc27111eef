// The ends of the range of what a bake can be asked for: nothing to bake (no geometry, or no
// light), the smallest grid, and a grid no machine could hold.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "bake/Baker.h"
#include "basis/BasisRegistry.h"
#include "common/Error.h"
#include "formats/VolumeReader.h"
#include "scene/RayTracer.h"
#include "tests/GltfTestAssets.h"
#include "tests/TestData.h"
#include "volume/MemoryEstimate.h"

namespace baker {
namespace {

class StressGridExtremes : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = test::makeTempDir(::testing::UnitTest::GetInstance()->current_test_info()->name()); }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  // Bakes `scene` with the command line, as a user would, and reads the volume back.
  Volume bake(const std::string& scene, const std::string& flags) const {
    const test::ProcessResult run = test::runBaker(dir_, "'" + scene + "' --out out.vdb --rays 32 --quiet " + flags);
    EXPECT_EQ(run.exitCode, 0) << run.err;
    return readVolume(dir_ + "/out.vdb");
  }
  static void expectBlack(const Volume& volume) {
    ASSERT_FALSE(volume.coefficients.empty());
    for (float c : volume.coefficients) ASSERT_EQ(c, 0.0f);
    for (float v : volume.visibility) ASSERT_TRUE(std::isfinite(v));
  }

  std::string dir_;
};

// No node at all: one probe at the origin, nothing to light it, every ray escaping.
TEST_F(StressGridExtremes, AnEmptySceneBakesAValidBlackVolume) {
  const Volume volume = bake(test::GltfBuilder().write(dir_, "empty"), "");
  EXPECT_EQ(volume.grid.dims, Eigen::Vector3i(1, 1, 1));
  expectBlack(volume);
  // Open sky all round: V = 1 for every normal (channel 0's SH l = 0 coefficient is √(4π)).
  EXPECT_NEAR(volume.visibility[0], std::sqrt(4.0 * M_PI), 1e-4);
}

// default_room with its panel switched off and no sky: the geometry, and no light anywhere.
TEST_F(StressGridExtremes, ASceneWithNoLightBakesAValidBlackVolume) {
  nlohmann::json room;
  std::ifstream(test::sourcePath("data/default_room/default_room.gltf")) >> room;
  for (nlohmann::json& material : room["materials"]) material.erase("emissiveFactor");
  std::ofstream(dir_ + "/dark_room.gltf") << room.dump();
  std::filesystem::copy_file(test::sourcePath("data/default_room/default_room.bin"), dir_ + "/default_room.bin");
  const Volume volume = bake(dir_ + "/dark_room.gltf", "--spacing 1");
  EXPECT_EQ(volume.grid.probeCount(), 4 * 3 * 4);
  expectBlack(volume);
}

// A spacing larger than the scene: one probe, baked, written, read and sampled like any other.
TEST_F(StressGridExtremes, AOneByOneByOneGridWorks) {
  const Volume volume = bake(test::sourcePath("data/default_room/default_room.gltf"), "--spacing 100");
  ASSERT_EQ(volume.grid.dims, Eigen::Vector3i(1, 1, 1));
  ASSERT_EQ(volume.states.size(), 1u);
  for (float c : volume.coefficients) ASSERT_TRUE(std::isfinite(c));
  EXPECT_GT(volume.coefficients[0], 0.0f);
  const test::ProcessResult sample = test::runBaker(dir_, "sample out.vdb --at 0,1.5,2 --normal 0,1,0 --json");
  EXPECT_EQ(sample.exitCode, 0) << sample.err;
  EXPECT_NE(sample.out.find("irradiance"), std::string::npos) << sample.out;
}

// 2^50 probes of sh-l8 would take some 3 EB: refused at once, before a ray or an operator, with
// the estimate in bytes.
TEST_F(StressGridExtremes, AGridTooLargeForMemoryIsRefusedBeforeTracingWithTheEstimate) {
  const Scene scene;
  const RayTracer tracer(scene);
  const auto basis = makeBasis("sh-l8");
  ProbeGrid grid;
  grid.dims = {1 << 20, 1 << 20, 1 << 10};
  const double estimate = bakeMemoryBytes(grid, 1, *basis);
  EXPECT_GT(estimate, 1e18);
  const auto start = std::chrono::steady_clock::now();
  try {
    bakeVolume(scene, tracer, *basis, grid, {}, nullptr);
    ADD_FAILURE() << "baked";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(fmt::format("needs about {:.0f} bytes", estimate)), std::string::npos) << message;
    EXPECT_NE(message.find("1048576 × 1048576 × 1024 probes in sh-l8"), std::string::npos) << message;
    EXPECT_NE(message.find("nothing was traced"), std::string::npos) << message;
  }
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 1.0);

  // What fits is let through, whatever the machine: the check compares with what it is given.
  grid.dims = {10, 10, 10};
  const double needed = bakeMemoryBytes(grid, 1, *basis);
  EXPECT_NO_THROW(requireVolumeFitsInMemory(grid, 1, *basis, std::uint64_t(needed)));
  EXPECT_THROW(requireVolumeFitsInMemory(grid, 1, *basis, std::uint64_t(needed) - 1), InputError);
  // A shard holds its run of whole bricks (and the brick tables), not the grid: 8 shards of 10³
  // probes in 8 bricks hold one full brick each, not an eighth of the probes.
  EXPECT_GE(bakeMemoryBytes(grid, 8, *basis), volumeMemoryBytes(512, *basis));
  ProbeGrid large;
  large.dims = {80, 80, 80};
  EXPECT_LT(bakeMemoryBytes(large, 8, *basis), bakeMemoryBytes(large, 1, *basis) / 7);
}

}  // namespace
}  // namespace baker
