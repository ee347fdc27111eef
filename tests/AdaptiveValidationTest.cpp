#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <set>

#include "basis/BasisRegistry.h"
#include "formats/VdbWriter.h"
#include "formats/VolumeReader.h"
#include "images/RgbImage.h"
#include "tests/BakerProcess.h"
#include "tests/GltfTestAssets.h"
#include "tests/SyntheticVolumes.h"
#include "tests/TestData.h"

// `baker validate` of adaptive volumes: each level's probes met one to one when the grids are the
// same, the volume read as an engine reads it otherwise, placement changes failing the check.
namespace baker {
namespace {

class AdaptiveValidation : public ::testing::Test {
 protected:
  // A ground and a small quad 6 m above it under a white sky, three levels at 0.5 m finest:
  // finer bricks only near the two quads. Baked twice, at margins 1 and 2 (more fine bricks).
  static void SetUpTestSuite() {
    dir_ = new std::string(test::makeTempDir("AdaptiveValidation"));
    test::GltfBuilder gltf;
    const auto quad = [&](const std::vector<float>& corners) {
      gltf.node({{"mesh", gltf.mesh({{"POSITION", gltf.floats(corners, "VEC3")}}, gltf.indices({0, 1, 2, 0, 2, 3}))}});
    };
    quad({-6, 0, -6, -6, 0, 6, 6, 0, 6, 6, 0, -6});
    quad({0, 6, 0, 1, 6, 0, 1, 6, 1, 0, 6, 1});
    gltf.write(*dir_, "ground");
    for (const char* margin : {"1", "2"}) {
      const test::ProcessResult bake =
          test::runBaker(*dir_, {"ground.gltf", "--placement", "adaptive", "--levels", "3", "--spacing", "0.5", "--rays",
                                 "32", "--sky", "1,1,1", "--margin", margin, "--out",
                                 std::string("margin") + margin + ".vdb", "--quiet"});
      ASSERT_EQ(bake.exitCode, 0) << bake.err;
    }
  }
  static void TearDownTestSuite() { delete dir_; }

  static nlohmann::json validate(const std::vector<std::string>& arguments, int expectedExit) {
    std::vector<std::string> all = {"validate"};
    all.insert(all.end(), arguments.begin(), arguments.end());
    all.push_back("--json");
    const test::ProcessResult run = test::runBaker(*dir_, all);
    EXPECT_EQ(run.exitCode, expectedExit) << run.err;
    return run.exitCode < 2 ? nlohmann::json::parse(run.out) : nlohmann::json();
  }
  static AdaptiveVolume baked() { return readLevels(*dir_ + "/margin1.vdb"); }
  static void write(const AdaptiveVolume& volume, const std::string& name) {
    writeAdaptiveVdb(volume, *makeBasis(volume.coarsest().basisName), *dir_ + "/" + name);
  }
  // Every held probe of every level set to smoothProbe's affine field of its position, which
  // trilinear reading at any level reproduces, plus `perLevel` times its level in each channel's
  // first coefficient: then what is read at a place also says from which level.
  static AdaptiveVolume affine(AdaptiveVolume volume, float perLevel = 0.0f) {
    const auto basis = makeBasis(volume.coarsest().basisName);
    for (std::size_t l = 0; l < volume.levels.size(); ++l) {
      Volume& level = volume.levels[l];
      std::fill(level.visibility.begin(), level.visibility.end(), 0.0f);
      for (std::int64_t row = 0; row < level.rows.count(level.grid); ++row) {
        float* coefficients = level.coefficients.data() + row * level.coefficientsPerProbe;
        test::smoothProbe(*basis, level.grid.position(level.rows.probeAt(level.grid, row)), coefficients,
                          level.visibility.data() + row * level.visibilityPerProbe);
        for (int channel = 0; channel < 3; ++channel) coefficients[basis->coefficientOffset(channel)] += perLevel * float(l);
      }
    }
    return volume;
  }
  // A uniform volume of the same field whose probes each carry the offset of the level an engine
  // reads at their place in `levels` (the level choice is checked against the decoders in
  // AdaptiveVolumeTest).
  static Volume uniformAsRead(const AdaptiveVolume& levels, const Eigen::Vector3i& dims, const Eigen::Vector3d& origin,
                              double spacing, float perLevel) {
    Volume v = test::smoothVolume(dims, origin, spacing);
    const auto basis = makeBasis(v.basisName);
    for (std::int64_t p = 0; p < v.grid.probeCount(); ++p) {
      const int level = finestLevelAt(levels.levels, int(levels.levels.size()), v.grid.position(p)).level;
      for (int channel = 0; channel < 3; ++channel)
        v.coefficients[std::size_t(p * v.coefficientsPerProbe + basis->coefficientOffset(channel))] += perLevel * float(level);
    }
    return v;
  }

  static std::string* dir_;
};
std::string* AdaptiveValidation::dir_ = nullptr;

TEST_F(AdaptiveValidation, MeetsEachLevelsOwnProbes) {
  const AdaptiveVolume volume = baked();
  ASSERT_EQ(volume.levels.size(), 3u);
  const nlohmann::json itself = validate({"margin1.vdb", "margin1.vdb"}, 0);
  EXPECT_EQ(itself["max_relative_error"].get<double>(), 0.0);
  EXPECT_EQ(itself["sky_visibility_max_abs_difference"].get<double>(), 0.0);
  // Read as decoders relight it under the sky it was baked under, it is itself to rounding.
  EXPECT_LT(validate({"margin1.vdb", "margin1.vdb", "--run-time-sky", "1,1,1"}, 0)["max_relative_error"].get<double>(),
            1e-4);

  // One finest-level probe 10 % brighter: it alone differs, named by its level and index.
  AdaptiveVolume brighter = volume;
  Volume& finest = brighter.levels[2];
  const std::int64_t row = finest.rows.count(finest.grid) / 2, p = finest.rows.probeAt(finest.grid, row);
  for (int c = 0; c < finest.coefficientsPerProbe; ++c) finest.coefficients[std::size_t(row * finest.coefficientsPerProbe + c)] *= 1.1f;
  write(brighter, "brighter.vdb");
  const nlohmann::json report = validate({"margin1.vdb", "brighter.vdb"}, 1);
  EXPECT_TRUE(report["grids_match"].get<bool>());
  EXPECT_EQ(report["placement_changes"], nlohmann::json({{"reference_only", 0}, {"new_only", 0}}));
  const nlohmann::json& worst = report["worst_probes"];
  ASSERT_GE(worst.size(), 2u);
  EXPECT_EQ(worst[0]["adaptive_level"].get<int>(), 2);
  const Eigen::Vector3i& n = finest.grid.dims;
  EXPECT_EQ(worst[0]["index"], nlohmann::json({p % n.x(), p / n.x() % n.y(), p / (std::int64_t(n.x()) * n.y())}));
  EXPECT_GE(worst[0]["relative_error"].get<double>(), 0.1 - 1e-6) << "10 % of each E(n), over the mean of E(n)";
  EXPECT_EQ(worst[1]["relative_error"].get<double>(), 0.0) << "every other probe meets its own";
  EXPECT_EQ(report["probes_compared"].get<std::int64_t>(),
            volume.levels[0].rows.count(volume.levels[0].grid) + volume.levels[1].rows.count(volume.levels[1].grid) +
                finest.rows.count(finest.grid));

  // A level-1 probe turned invalid is a validity change at level 1.
  AdaptiveVolume invalid = volume;
  invalid.levels[1].states[0] = ProbeState::Invalid;
  write(invalid, "invalid.vdb");
  const nlohmann::json changes = validate({"margin1.vdb", "invalid.vdb"}, 1)["validity_changes"];
  ASSERT_EQ(changes.size(), 1u);
  EXPECT_EQ(changes[0]["adaptive_level"].get<int>(), 1);
  EXPECT_EQ(changes[0]["new"].get<std::string>(), "invalid");
}

// An affine field in every level reads the same as a uniform volume of the same field on another
// grid, both ways: the adaptive volume is read at the finest level holding the probes around each
// uniform probe (each level's field offset by its own constant, so that the level matters), and
// each of its held probes is met by the uniform volume read there.
TEST_F(AdaptiveValidation, ReadsAnAdaptiveVolumeAsAnEngineDoes) {
  constexpr float kPerLevel = 0.25f;
  const AdaptiveVolume levelled = affine(baked(), kPerLevel);
  write(levelled, "levelled.vdb");
  const ProbeGrid& box = levelled.coarsest().grid;
  // Inside the coarsest level's probes (so that no reading clamps), on a grid of its own.
  const Eigen::Vector3d inside = box.origin + Eigen::Vector3d::Constant(0.3);
  const Eigen::Vector3i dims(9, 5, 9);
  const double spacing = (box.spacing * (box.dims.minCoeff() - 1) - 0.7) / 8;
  const Volume within = uniformAsRead(levelled, dims, inside, spacing, kPerLevel);
  ASSERT_LE((inside + spacing * (dims.cast<double>().array() - 1).matrix() - box.origin).maxCoeff(),
            box.spacing * (box.dims.minCoeff() - 1));
  std::set<int> served;
  for (std::int64_t p = 0; p < within.grid.probeCount(); ++p)
    served.insert(finestLevelAt(levelled.levels, 3, within.grid.position(p)).level);
  EXPECT_GE(served.size(), 2u) << "the uniform probes are read from more than one level";
  writeVdb(within, *makeBasis("sh-l2"), *dir_ + "/within.vdb");
  nlohmann::json report = validate({"within.vdb", "levelled.vdb"}, 0);
  EXPECT_FALSE(report["grids_match"].get<bool>());
  EXPECT_TRUE(report["placement_changes"].is_null());
  EXPECT_EQ(report["probes_compared"].get<std::int64_t>(), within.grid.probeCount());
  EXPECT_LT(report["max_relative_error"].get<double>(), 1e-5);
  // Read from level 0 alone, the adaptive volume would be off where a finer level serves.
  writeVdb(uniformAsRead(levelled, dims, inside, spacing, 0.0f), *makeBasis("sh-l2"), *dir_ + "/level0.vdb");
  EXPECT_GT(validate({"level0.vdb", "levelled.vdb"}, 1)["max_relative_error"].get<double>(), 0.01);

  const AdaptiveVolume field = affine(baked());
  write(field, "affine.vdb");

  // A uniform volume around the whole box: every held probe of every level compared.
  const Volume around = test::smoothVolume((box.dims.array() + 2).matrix(), box.origin.array() - box.spacing, box.spacing);
  writeVdb(around, *makeBasis("sh-l2"), *dir_ + "/around.vdb");
  report = validate({"affine.vdb", "around.vdb"}, 0);
  std::int64_t held = 0;
  for (const Volume& level : field.levels) held += level.rows.count(level.grid);
  EXPECT_EQ(report["probes_compared"].get<std::int64_t>(), held);
  EXPECT_LT(report["max_relative_error"].get<double>(), 1e-5);
  EXPECT_EQ(report["metadata_differences"].back()["field"].get<std::string>(), "levels");

  // The same field one probe off at the finest level fails there.
  AdaptiveVolume off = field;
  Volume& finest = off.levels[2];
  for (int c = 0; c < finest.coefficientsPerProbe; ++c) finest.coefficients[std::size_t(c)] += 1.0f;
  write(off, "off.vdb");
  report = validate({"off.vdb", "around.vdb"}, 1);
  EXPECT_GT(report["max_relative_error"].get<double>(), 0.01);
  EXPECT_EQ(report["worst_probes"][0]["adaptive_level"].get<int>(), 2);
  EXPECT_LT(report["worst_probes"][1]["relative_error"].get<double>(), 1e-5);
}

TEST_F(AdaptiveValidation, PlacementChangesFail) {
  const nlohmann::json report = validate({"margin1.vdb", "margin2.vdb"}, 1);
  EXPECT_TRUE(report["grids_match"].get<bool>());
  EXPECT_EQ(report["placement_changes"]["reference_only"].get<std::int64_t>(), 0) << "a wider margin places more";
  EXPECT_GT(report["placement_changes"]["new_only"].get<std::int64_t>(), 0);
  bool failed = false;
  for (const nlohmann::json& check : report["checks"])
    if (check["name"] == "placement unchanged") failed = !check["passed"].get<bool>();
  EXPECT_TRUE(failed);
}

// Against reference panoramas of a constant sky L, E(n) = πL everywhere. An adaptive volume holding
// that constant times 1 + 0.1 × level is off at each reference inside it by 0.1 × the level an
// engine reads there, over the mean of L's channels; one outside is counted so.
TEST_F(AdaptiveValidation, AgainstReferencePanoramas) {
  AdaptiveVolume constant = baked();
  const auto basis = makeBasis(constant.coarsest().basisName);
  std::vector<float> unit(std::size_t(basis->totalCoefficients()), 0.0f);
  for (int channel = 0; channel < 3; ++channel) unit[std::size_t(basis->coefficientOffset(channel))] = 1.0f;
  const Eigen::Vector3f radiance(0.5f, 0.25f, 0.125f);
  const Eigen::Vector3f perUnit = basis->reconstruct(unit.data(), Eigen::Vector3d::UnitY());
  for (std::size_t l = 0; l < constant.levels.size(); ++l) {
    Volume& level = constant.levels[l];
    for (std::int64_t row = 0; row < level.rows.count(level.grid); ++row)
      for (int channel = 0; channel < 3; ++channel) {
        float* c = level.coefficients.data() + row * level.coefficientsPerProbe + basis->coefficientOffset(channel);
        std::fill(c, c + basis->functions(channel).count(), 0.0f);
        c[0] = float(M_PI) * radiance[channel] * (1.0f + 0.1f * float(l)) / perUnit[channel];
      }
  }
  write(constant, "constant.vdb");
  const std::string references = *dir_ + "/references";
  std::filesystem::create_directories(references);
  test::writeReferenceDirectory(references, {{0.2, 0.4, 0.3}, {-3.1, 2.0, 4.4}, {0.0, 400.0, 0.0}},
                                test::constantPanorama(256, 128, radiance), 2);
  const nlohmann::json report =
      validate({"constant.vdb", "--against-reference", "references", "--tolerance", "1"}, 0);
  EXPECT_EQ(report["probes_compared"].get<int>(), 2);
  EXPECT_EQ(report["probes_outside_new_grid"].get<int>(), 1);
  std::set<int> levels;
  for (const nlohmann::json& probe : report["worst_probes"]) {
    const std::vector<double> at = probe["position"].get<std::vector<double>>();
    const int level = finestLevelAt(constant.levels, 3, Eigen::Vector3d(at[0], at[1], at[2])).level;
    levels.insert(level);
    EXPECT_NEAR(probe["relative_error"].get<double>(), 0.1 * level * radiance.maxCoeff() / radiance.mean(), 1e-3);
  }
  EXPECT_EQ(levels.size(), 2u) << "the two references are read from two levels";
}

// `baker preview` of an adaptive volume draws its slices on the finest level's grid. With the affine
// field in every level, offset by a constant per level, each cell shows the field at its place plus
// the offset of the finest level holding a probe there or, within the coarsest level's probes
// (where no level's reading clamps), of the level an engine reads there.
TEST_F(AdaptiveValidation, PreviewShowsTheSlicesOnTheFinestGrid) {
  constexpr float kPerLevel = 0.25f;
  AdaptiveVolume field = affine(baked(), kPerLevel);
  for (Volume& level : field.levels) std::fill(level.states.begin(), level.states.end(), ProbeState::Valid);
  write(field, "affine_preview.vdb");
  constexpr double kExposure = 0.5;
  const test::ProcessResult run =
      test::runBaker(*dir_, {"preview", "affine_preview.vdb", "--out", "p.png", "--exposure", "0.5", "--json"});
  ASSERT_EQ(run.exitCode, 0) << run.err;
  const nlohmann::json legend = nlohmann::json::parse(run.out);
  const ProbeGrid& g = field.levels.back().grid;
  const int j = g.dims.y() / 2;
  EXPECT_EQ(legend["xz_slice"]["j"].get<int>(), j);
  EXPECT_NEAR(legend["xz_slice"]["y"].get<double>(), g.position(0, j, 0).y(), 1e-9);
  const std::vector<int> cells = legend["cells_by_level"].get<std::vector<int>>();
  ASSERT_EQ(cells.size(), 3u);
  EXPECT_EQ(cells[0] + cells[1] + cells[2], g.dims.x() * (g.dims.z() + g.dims.y()));
  EXPECT_GT(cells[2], 0) << "near the ground";
  EXPECT_GT(cells[0] + cells[1], 0) << "in the air above it";
  const int cell = legend["cell_pixels"].get<int>();
  EXPECT_EQ(legend["width"].get<int>(), 8 + 3 * (g.dims.x() * cell + 8));

  // E(+Y) of the field through the documented tone curve and sRGB's byte encoding.
  const auto basis = makeBasis("sh-l2");
  std::vector<float> coefficients(27), visibility(9, 0.0f);
  const auto expectedByte = [&](const Eigen::Vector3d& x, int level, int channel) {
    test::smoothProbe(*basis, x, coefficients.data(), visibility.data());
    for (int c = 0; c < 3; ++c) coefficients[std::size_t(basis->coefficientOffset(c))] += kPerLevel * float(level);
    const double e = kExposure * basis->reconstruct(coefficients.data(), Eigen::Vector3d::UnitY())[channel];
    const double shown = e / (1.0 + e);
    const double encoded = shown <= 0.0031308 ? 12.92 * shown : 1.055 * std::pow(shown, 1.0 / 2.4) - 0.055;
    return 255.0 * encoded;
  };
  const RgbImage image = readRgbImage(*dir_ + "/p.png");
  const ProbeGrid& box = field.coarsest().grid;
  const Eigen::Vector3d far = box.origin + box.spacing * (box.dims.cast<double>().array() - 1).matrix();
  // The finest level holding a probe at x, which shows as it is, clamped or not; -1 for none.
  const auto heldBy = [&](const Eigen::Vector3d& x) {
    for (int l = 2; l >= 0; --l) {
      const Volume& level = field.levels[std::size_t(l)];
      const Eigen::Vector3d index = ((x - level.grid.origin) / level.grid.spacing).array().round();
      if (((x - level.grid.origin) / level.grid.spacing - index).cwiseAbs().maxCoeff() > 1e-6) continue;
      if ((index.array() >= 0).all() && (index.array() < level.grid.dims.cast<double>().array()).all() &&
          level.rows.row(level.grid, int(index.x()), int(index.y()), int(index.z())) >= 0)
        return l;
    }
    return -1;
  };
  int checked[2] = {0, 0};  // cells showing a held probe, and read between probes
  const int xySliceTop = 8 + g.dims.z() * cell + 8, k = g.dims.z() / 2;
  for (int i = 0; i < g.dims.x(); ++i)
    for (int r = 0; r < g.dims.z() + g.dims.y(); ++r) {
      // Rows of the XZ slice (z down), then of the XY slice (y up).
      const bool xz = r < g.dims.z();
      const Eigen::Vector3d x = xz ? g.position(i, j, r) : g.position(i, g.dims.y() - 1 - (r - g.dims.z()), k);
      const int holder = heldBy(x);
      const bool probe = holder >= 0;
      if (!probe && ((x - box.origin).minCoeff() < 0.0 || (far - x).minCoeff() < 0.0)) continue;
      const int level = probe ? holder : finestLevelAt(field.levels, 3, x).level;
      const int top = xz ? 8 + r * cell : xySliceTop + (r - g.dims.z()) * cell;
      const float* pixel = image.pixel(top + cell / 2, 8 + i * cell + cell / 2);
      for (int channel = 0; channel < 3; ++channel)
        EXPECT_NEAR(255.0 * pixel[channel], expectedByte(x, level, channel), 1.0) << i << " " << r << " channel " << channel;
      ++checked[probe ? 0 : 1];
    }
  EXPECT_GT(checked[0], 20);
  EXPECT_GT(checked[1], 20);

  // The baked volume: the same cells by level.
  const test::ProcessResult baked = test::runBaker(*dir_, {"preview", "margin1.vdb", "--out", "b.png", "--json"});
  ASSERT_EQ(baked.exitCode, 0) << baked.err;
  EXPECT_EQ(nlohmann::json::parse(baked.out)["cells_by_level"].get<std::vector<int>>(), cells);
}

// A damaged adaptive file: both commands name it, exit 2, and write nothing.
TEST_F(AdaptiveValidation, DamagedAdaptiveFilesAreRefused) {
  const std::string whole = *dir_ + "/margin1.vdb", cut = *dir_ + "/cut.vdb";
  std::filesystem::copy_file(whole, cut, std::filesystem::copy_options::overwrite_existing);
  std::filesystem::resize_file(cut, std::filesystem::file_size(whole) / 2);
  const test::ProcessResult preview = test::runBaker(*dir_, {"preview", "cut.vdb", "--out", "cut.png"});
  EXPECT_EQ(preview.exitCode, 2);
  EXPECT_NE(preview.err.find("cut.vdb"), std::string::npos) << preview.err;
  EXPECT_FALSE(std::filesystem::exists(*dir_ + "/cut.png"));
  const test::ProcessResult validate =
      test::runBaker(*dir_, {"validate", "margin1.vdb", "cut.vdb", "--report", "cut.json"});
  EXPECT_EQ(validate.exitCode, 2);
  EXPECT_NE(validate.err.find("cut.vdb"), std::string::npos) << validate.err;
  EXPECT_FALSE(std::filesystem::exists(*dir_ + "/cut.json"));
}

}  // namespace
}  // namespace baker
