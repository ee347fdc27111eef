#include <fmt/format.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "tests/BakerProcess.h"
#include "tests/TestData.h"

namespace baker {
namespace {


std::vector<std::string> filesIn(const std::string& dir) {
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(dir)) names.push_back(entry.path().string());
  return names;
}

class BadInput : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = test::makeTempDir(::testing::UnitTest::GetInstance()->current_test_info()->name());
    scene_ = test::sourcePath("data/default_room/default_room.gltf");
  }
  // One line on stderr that mentions `needle`, exit code 2, and nothing written.
  void expectRejected(const std::string& args, const std::string& needle,
                      const std::vector<std::string>& keep = {}) {
    const test::ProcessResult run = test::runBaker(dir_, args);
    EXPECT_EQ(run.exitCode, 2) << run.err;
    EXPECT_NE(run.err.find(needle), std::string::npos) << run.err;
    EXPECT_EQ(std::count(run.err.begin(), run.err.end(), '\n'), 1) << run.err;
    EXPECT_EQ(filesIn(dir_), keep) << "no output may be left behind";
  }
  std::string dir_, scene_;
};

// Coefficients >= 0 bound nothing when the functions themselves change sign.
TEST_F(BadInput, NonNegativeWithSignChangingFunctions) {
  for (const char* basis : {"sh-l2", "ad-rgb", "ad-ycocg"})
    expectRejected(fmt::format("'{}' --basis {} --non-negative --out out.vdb", scene_, basis),
                   fmt::format("--non-negative does not apply to {}: its functions change sign", basis));
}

TEST_F(BadInput, MissingSceneFile) { expectRejected("no_such_scene.gltf --out out.vdb", "no_such_scene.gltf"); }

TEST_F(BadInput, MalformedSceneFile) {
  const std::string bad = dir_ + "/broken.gltf";
  std::ofstream(bad) << "{ \"asset\": { \"version\": \"2.0\" }, \"meshes\": [ {";
  expectRejected("broken.gltf --out out.vdb", "broken.gltf", {bad});
}

TEST_F(BadInput, SceneWithAnAccessorOutOfRange) {
  const std::string bad = dir_ + "/short.gltf";
  // 3 vertices need 36 bytes; the buffer (a data URI of 12 zero bytes) has 12.
  std::ofstream(bad) << R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],
    "meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],
    "accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3"}],
    "bufferViews":[{"buffer":0,"byteLength":12}],
    "buffers":[{"byteLength":12,"uri":"data:application/octet-stream;base64,AAAAAAAAAAAAAAAA"}]})";
  expectRejected("short.gltf --out out.vdb", "meshes[0].primitives[0].attributes.POSITION", {bad});
}

TEST_F(BadInput, UnknownBasis) { expectRejected("'" + scene_ + "' --basis sh-l99 --out out.vdb", "sh-l99"); }

TEST_F(BadInput, ZeroSpacing) { expectRejected("'" + scene_ + "' --spacing 0 --out out.vdb", "--spacing"); }

TEST_F(BadInput, NegativeSpacing) { expectRejected("'" + scene_ + "' --spacing -0.5 --out out.vdb", "--spacing"); }

TEST_F(BadInput, SgSharpnessForAnotherBasis) {
  expectRejected("'" + scene_ + "' --basis ad-srbf --sg-sharpness 2 --out out.vdb", "--sg-sharpness");
}

TEST_F(BadInput, UnknownQuality) {
  expectRejected("'" + scene_ + "' --quality best --out out.vdb", "--quality must be one of draft, default, final");
}

TEST_F(BadInput, QualityAndAFixedRayCount) {
  expectRejected("'" + scene_ + "' --quality draft --rays 64 --out out.vdb", "--rays");
}

TEST_F(BadInput, NegativeWindow) { expectRejected("'" + scene_ + "' --window -1 --out out.vdb", "--window"); }

TEST_F(BadInput, OutputInAMissingDirectory) {
  expectRejected("'" + scene_ + "' --out no_such_dir/out.vdb", "no_such_dir");
}

TEST_F(BadInput, ValidBakeWritesExactlyTheVolume) {
  const test::ProcessResult run = test::runBaker(dir_, "'" + scene_ + "' --spacing 1 --rays 32 --out out.vdb");
  EXPECT_EQ(run.exitCode, 0) << run.err;
  EXPECT_EQ(filesIn(dir_), std::vector<std::string>{dir_ + "/out.vdb"});
}

}  // namespace
}  // namespace baker
