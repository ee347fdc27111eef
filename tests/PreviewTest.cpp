#include <gtest/gtest.h>

#include <array>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <set>

#include "basis/BasisRegistry.h"
#include "formats/VdbWriter.h"
#include "images/RgbImage.h"
#include "tests/GltfTestAssets.h"
#include "tests/SyntheticVolumes.h"
#include "tests/TestData.h"

// `baker preview`: a PNG of the expected layout that shows something, marks what it promises to mark.
namespace baker {
namespace {

const Eigen::Vector3i kDims(16, 16, 16);
const Eigen::Vector3d kOrigin(-2.0, 0.0, -2.0);
constexpr double kSpacing = 0.25;

// 16³ probes get 16-pixel cells: three 256-pixel panels and four 8-pixel margins across; two rows
// of 256, the colour bar (16) and its ticks (6) with their margins down.
constexpr int kWidth = 8 + 3 * (256 + 8);
constexpr int kHeight = 8 + 256 + 8 + 256 + 8 + 16 + 6 + 8;

std::size_t countColour(const RgbImage& image, const std::array<float, 3>& colour) {
  std::size_t count = 0;
  for (std::size_t p = 0; p < image.pixels.size(); p += 3)
    count += image.pixels[p] == colour[0] && image.pixels[p + 1] == colour[1] && image.pixels[p + 2] == colour[2];
  return count;
}

std::size_t distinctColours(const RgbImage& image) {
  std::set<std::array<float, 3>> colours;
  for (std::size_t p = 0; p < image.pixels.size(); p += 3)
    colours.insert({image.pixels[p], image.pixels[p + 1], image.pixels[p + 2]});
  return colours.size();
}

class Preview : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = test::makeTempDir(::testing::UnitTest::GetInstance()->current_test_info()->name());
    volume_ = test::smoothVolume(kDims, kOrigin, kSpacing);
  }
  void writeVolume() { writeVdb(volume_, *makeBasis(volume_.basisName), dir_ + "/volume.vdb"); }

  std::string dir_;
  Volume volume_;
};

TEST_F(Preview, ShowsTheMiddleSlicesAtTheDocumentedSize) {
  writeVolume();
  const test::ProcessResult run = test::runBaker(dir_, "preview volume.vdb --out preview.png --json");
  ASSERT_EQ(run.exitCode, 0) << run.out << run.err;
  const nlohmann::json legend = nlohmann::json::parse(run.out);
  EXPECT_EQ(legend["cell_pixels"].get<int>(), 16);
  EXPECT_EQ(legend["xz_slice"]["j"].get<int>(), 8);
  EXPECT_GT(legend["exposure"].get<double>(), 0.0);
  const RgbImage image = readRgbImage(dir_ + "/preview.png");
  EXPECT_EQ(image.width, kWidth);
  EXPECT_EQ(image.height, kHeight);
  EXPECT_GT(distinctColours(image), 50u) << "irradiance varies across the slices";
  EXPECT_EQ(countColour(image, {1.0f, 0.0f, 0.0f}), 0u) << "no invalid probe, no red cross";
  EXPECT_EQ(countColour(image, {0.0f, 1.0f, 1.0f}), 0u) << "no relocated probe, no cyan square";
  for (const auto& entry : std::filesystem::directory_iterator(dir_))
    EXPECT_EQ(entry.path().filename().string().find(".tmp-"), std::string::npos) << "written through a temporary file";
}

TEST_F(Preview, MarksInvalidAndRelocatedProbes) {
  volume_.states[volume_.grid.linearIndex(3, 8, 5)] = ProbeState::Invalid;     // in the XZ slice (j = 8)
  volume_.states[volume_.grid.linearIndex(10, 2, 8)] = ProbeState::Relocated;  // in the XY slice (k = 8)
  writeVolume();
  const test::ProcessResult run = test::runBaker(dir_, "preview volume.vdb --out preview.png --exposure 0.2");
  ASSERT_EQ(run.exitCode, 0) << run.out << run.err;
  EXPECT_NE(run.out.find("1 invalid probes (red cross), 1 relocated"), std::string::npos) << run.out;
  const RgbImage image = readRgbImage(dir_ + "/preview.png");
  // Each of the three panels of its slice marks the probe.
  EXPECT_GE(countColour(image, {1.0f, 0.0f, 0.0f}), 3u * 2 * 14);
  EXPECT_GE(countColour(image, {0.0f, 1.0f, 1.0f}), 3u * 5 * 5);
}

TEST_F(Preview, DrawsAProbeSphereBesideTheReferencePanorama) {
  writeVolume();
  std::filesystem::create_directory(dir_ + "/ref");
  test::writeReferenceDirectory(dir_ + "/ref", {{0, 2, 0}, {0.5, 1.0, 0.5}},
                                test::constantPanorama(64, 32, Eigen::Vector3f(1.0f, 0.5f, 0.25f)), 2);
  const test::ProcessResult run =
      test::runBaker(dir_, "preview volume.vdb --out preview.png --probe 0.4,1.1,0.4 --reference ref --json");
  ASSERT_EQ(run.exitCode, 0) << run.out << run.err;
  const nlohmann::json legend = nlohmann::json::parse(run.out);
  EXPECT_EQ(legend["reference_probe"]["index"].get<int>(), 1);
  const RgbImage image = readRgbImage(dir_ + "/preview.png");
  EXPECT_EQ(image.width, kWidth);
  EXPECT_EQ(image.height, kHeight + 128 + 8) << "a row of 256 × 128 spheres";
  // The reference's radiance panorama (third sphere) is the constant sky: one colour, warm.
  const float* sky = image.pixel(kHeight + 64, 8 + 2 * (256 + 8) + 128);
  EXPECT_GT(sky[0], sky[1]);
  EXPECT_GT(sky[1], sky[2]);
  EXPECT_EQ(sky[0], image.pixel(kHeight + 10, 8 + 2 * (256 + 8) + 10)[0]);
}

TEST_F(Preview, RejectsWhatItCannotDraw) {
  writeVolume();
  EXPECT_EQ(test::runBaker(dir_, "preview missing.vdb --out p.png").exitCode, 2);
  EXPECT_EQ(test::runBaker(dir_, "preview volume.vdb --out p.png --exposure 0").exitCode, 2);
  EXPECT_EQ(test::runBaker(dir_, "preview volume.vdb --out p.png --reference ref").exitCode, 2) << "needs --probe";
  EXPECT_EQ(test::runBaker(dir_, "preview volume.vdb --out p.png --probe 1,2").exitCode, 2);
  EXPECT_EQ(test::runBaker(dir_, "preview volume.vdb --out nowhere/p.png").exitCode, 2);
  EXPECT_FALSE(std::filesystem::exists(dir_ + "/p.png"));
}

}  // namespace
}  // namespace baker
