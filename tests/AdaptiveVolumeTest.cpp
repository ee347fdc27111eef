#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <random>

#include "bake/AdaptiveBaker.h"
#include "bake/AdaptivePlacement.h"
#include "bake/TriangleBoxOverlap.h"
#include "basis/BasisRegistry.h"
#include "common/Error.h"
#include "decoders/baker_irradiance.h"
#include "formats/ExrLevels.h"
#include "formats/VdbReader.h"
#include "formats/VolumeReader.h"
#include "formats/VdbWriter.h"
#include "scene/GltfLoader.h"
#include "tests/BakerProcess.h"
#include "tests/GltfTestAssets.h"
#include "tests/OnThreads.h"
#include "tests/TestData.h"
#include "volume/StoredBricks.h"

namespace baker {
namespace {

using Eigen::Vector3d;

TEST(TriangleBoxOverlap, SeparatingAxesDecide) {
  const Eigen::AlignedBox3d box(Vector3d(0, 0, 0), Vector3d(1, 1, 1));
  // Inside, far away, and touching a face.
  EXPECT_TRUE(triangleOverlapsBox({0.2, 0.2, 0.5}, {0.8, 0.2, 0.5}, {0.5, 0.8, 0.5}, box));
  EXPECT_FALSE(triangleOverlapsBox({5, 5, 5}, {6, 5, 5}, {5, 6, 5}, box));
  EXPECT_TRUE(triangleOverlapsBox({1, 0.2, 0.2}, {2, 0.2, 0.2}, {1, 0.8, 0.8}, box));
  // A large triangle slicing through the box, no corner inside it.
  EXPECT_TRUE(triangleOverlapsBox({-10, -10, 0.5}, {10, -10, 0.5}, {0, 20, 0.5}, box));
  // Its axis-aligned bounds overlap the box, but its plane passes by the corner (1, 1, 1):
  // x + y + z = 3.2 stays off the box, whose farthest corner has 3.
  EXPECT_FALSE(triangleOverlapsBox({3.2, 0, 0}, {0, 3.2, 0}, {0, 0, 3.2}, box));
  EXPECT_TRUE(triangleOverlapsBox({2.9, 0, 0}, {0, 2.9, 0}, {0, 0, 2.9}, box));
  // Bounds overlap, plane crosses the box, but an edge-cross-axis separates them: a thin sliver
  // passing beside the edge x = 1, y = 1.
  EXPECT_FALSE(triangleOverlapsBox({1.5, 0.9, -1}, {1.5, 0.9, 2}, {0.9, 1.5, 0.5}, box));
}

// Every probe of a level sits on a probe of the next finer level, and each coarser level covers
// the finer one.
TEST(LevelGrids, NestOnOneLatticeAndCoverTheBounds) {
  const Eigen::AlignedBox3f bounds(Eigen::Vector3f(-2, 0, -2), Eigen::Vector3f(2, 3, 2.1f));
  const ProbeGrid finest = makeProbeGrid(bounds, 0.25, 1 << 20);
  const std::vector<ProbeGrid> grids = levelGrids(finest, 3);
  ASSERT_EQ(grids.size(), 3u);
  for (int level = 1; level < 3; ++level) {
    const ProbeGrid& coarse = grids[level - 1];
    const ProbeGrid& fine = grids[level];
    EXPECT_TRUE(nestsIn(fine, coarse));
    EXPECT_FALSE(nestsIn(coarse, fine));
    EXPECT_NEAR(fine.spacing * kLevelRatio, coarse.spacing, 1e-12);
    for (int k = 0; k < coarse.dims.z(); ++k)
      for (int j = 0; j < coarse.dims.y(); ++j)
        for (int i = 0; i < coarse.dims.x(); ++i) {
          const Vector3d index = (coarse.position(i, j, k) - fine.origin) / fine.spacing;
          EXPECT_LT((index - index.array().round().matrix()).cwiseAbs().maxCoeff(), 1e-9) << i << " " << j << " " << k;
        }
    // The coarse cells cover the fine ones, by less than a coarse cell more.
    for (int a = 0; a < 3; ++a) {
      EXPECT_LE(coarse.origin[a] - 0.5 * coarse.spacing, fine.origin[a] - 0.5 * fine.spacing + 1e-9);
      EXPECT_GE(coarse.origin[a] + (coarse.dims[a] - 0.5) * coarse.spacing, fine.origin[a] + (fine.dims[a] - 0.5) * fine.spacing - 1e-9);
      EXPECT_LT(coarse.dims[a] * coarse.spacing, fine.dims[a] * fine.spacing + coarse.spacing);
    }
  }
  // The finest level is the uniform grid at 0.25 m, half a cell inside the walls.
  EXPECT_EQ(grids[2].dims, Eigen::Vector3i(16, 12, 17));
  EXPECT_EQ(grids[0].dims, Eigen::Vector3i(2, 2, 2));
  ProbeGrid shifted = grids[1];
  shifted.origin.x() += 0.1;
  EXPECT_FALSE(nestsIn(grids[2], shifted));
}

// A 48 m ground, a small panel 60 m up (so that the grid has air above), and a lamp 1.5 m
// over the ground: irradiance changes fast near the ground and slowly above.
class AdaptiveBake : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    test::GltfBuilder gltf;
    const auto quad = [&](const std::vector<float>& corners) {
      gltf.node({{"mesh", gltf.mesh({{"POSITION", gltf.floats(corners, "VEC3")}}, gltf.indices({0, 1, 2, 0, 2, 3}))}});
    };
    quad({-24, 0, -24, -24, 0, 24, 24, 0, 24, 24, 0, -24});
    quad({0, 60, 0, 1, 60, 0, 1, 60, 1, 0, 60, 1});
    const std::string dir = test::makeTempDir("AdaptiveBake");
    scene_ = new Scene(loadGltf(gltf.write(dir, "ground")));
    PunctualLight lamp;
    lamp.position = Eigen::Vector3f(0.0f, 1.5f, 0.0f);
    lamp.intensity = 200.0f;
    scene_->lights.push_back(lamp);
    tracer_ = new RayTracer(*scene_);
    basis_ = makeBasis("sh-l2").release();
    const ProbeGrid finest = makeProbeGrid(scene_->bounds, 1.0, 1 << 24);
    placement_ = new AdaptivePlacement(placeAdaptive(*scene_, *tracer_, finest, 3, 1, 1 << 24));
    settings_.rays = 32;
    settings_.transport.bounces = 1;
    settings_.transport.punctualLights = true;
    settings_.transport.directPunctual = true;
    settings_.transport.probeValidity = true;
    volume_ = new AdaptiveVolume(bakeAdaptive(*scene_, *tracer_, *basis_, *placement_, settings_, &stats_));
  }
  static void TearDownTestSuite() {
    delete volume_;
    delete placement_;
    delete basis_;
    delete tracer_;
    delete scene_;
  }

  // Irradiance (mean of R, G, B) facing `normal` where an engine samples the volume at `at`.
  static double irradiance(const AdaptiveVolume& v, const Vector3d& at, const Vector3d& normal) {
    std::vector<float> coefficients(std::size_t(v.coarsest().coefficientsPerProbe));
    std::vector<float> visibility(std::size_t(v.coarsest().visibilityPerProbe));
    sampleLevels(v.levels, int(v.levels.size()), at, coefficients.data(), visibility.data());
    return double(basis_->reconstruct(coefficients.data(), normal).mean());
  }

  static Scene* scene_;
  static RayTracer* tracer_;
  static Basis* basis_;
  static AdaptivePlacement* placement_;
  static BakeSettings settings_;
  static BakeStats stats_;
  static AdaptiveVolume* volume_;
};
Scene* AdaptiveBake::scene_ = nullptr;
RayTracer* AdaptiveBake::tracer_ = nullptr;
Basis* AdaptiveBake::basis_ = nullptr;
AdaptivePlacement* AdaptiveBake::placement_ = nullptr;
BakeSettings AdaptiveBake::settings_;
BakeStats AdaptiveBake::stats_;
AdaptiveVolume* AdaptiveBake::volume_ = nullptr;

TEST_F(AdaptiveBake, FineBricksOnlyNearGeometry) {
  const AdaptivePlacement& p = *placement_;
  ASSERT_EQ(p.levels(), 3);
  EXPECT_EQ(std::int64_t(p.bricks[0].size()), p.grids[0].brickCount()) << "level 0 covers the scene";
  for (int level = 1; level < 3; ++level) {
    const ProbeGrid& g = p.grids[std::size_t(level)];
    EXPECT_GT(p.bricks[std::size_t(level)].size(), 0u);
    EXPECT_LT(std::int64_t(p.bricks[std::size_t(level)].size()), g.brickCount()) << "level " << level << " fills the air";
    std::int64_t partial = 0;
    const ProbeRows rows = p.rows(level);
    for (const std::int64_t b : p.bricks[std::size_t(level)]) {
      // A sub-brick is placed exactly when the ground (y = 0) or the panel (y = 60) lies within
      // its reach.
      partial += rows.subBricks(g, b) != subBricksInGrid(g, b);
      const Eigen::Vector3i corner = g.brickCorner(b), extent = g.brickExtent(b);
      for (int s = 0; s < 8; ++s) {
        if (!(subBricksInGrid(g, b) & (1 << s))) continue;
        const Eigen::Vector3i first = corner + kSubBrickSize * Eigen::Vector3i(s & 1, (s >> 1) & 1, (s >> 2) & 1);
        const Eigen::Vector3i last = (first.array() + kSubBrickSize).min(corner.array() + extent.array()) - 1;
        // The placement's reach: its margin and one cell more (so that probes within the margin
        // have every neighbour placed).
        const double reach = (p.marginCells + 1) * g.spacing;
        const Vector3d lo = g.position(first.x(), first.y(), first.z()).array() - reach;
        const Vector3d hi = g.position(last.x(), last.y(), last.z()).array() + reach;
        const auto overlaps = [&](const Vector3d& a, const Vector3d& b) { return (lo.array() <= b.array()).all() && (hi.array() >= a.array()).all(); };
        const bool near = overlaps({-24, 0, -24}, {24, 0, 24}) || overlaps({0, 60, 0}, {1, 60, 1});
        EXPECT_EQ(rows.row(g, first.x(), first.y(), first.z()) >= 0, near) << "level " << level << " brick " << b << " sub-brick " << s;
      }
    }
    EXPECT_GT(partial, 0) << "level " << level << ": sub-bricks away from the surfaces are left out";
  }
  EXPECT_LT(p.probes(), std::int64_t(probesPerAxis(scene_->bounds, 1.0).prod())) << "fewer probes than uniform at 1 m";
  EXPECT_GT(stats_.interpolatedProbes, 0);
}

// The test: along a line crossing level boundaries, sampled irradiance has no jump
// larger than the largest step between neighbouring probes on either side; in fact none at all
// beyond float rounding at the change of level itself, because a finer level's border probes
// hold the coarser interpolation.
TEST_F(AdaptiveBake, NoJumpWhereTheLevelChanges) {
  const Vector3d normal = Vector3d(1, -1, 0).normalized();
  const double step = 0.01;
  int crossings = 0;
  for (const double x : {5.3, -11.6, 17.2}) {
    int previousLevel = -1;
    double previous = 0.0;
    for (double y = 0.5; y < 59.5; y += step) {
      const Vector3d at(x, y, 3.7);
      const int level = finestLevelAt(volume_->levels, 3, at).level;
      const double e = irradiance(*volume_, at, normal);
      if (previousLevel >= 0 && level != previousLevel) {
        ++crossings;
        // The largest step between neighbouring probes of either level along the line.
        double probeStep = 0.0;
        for (const int l : {level, previousLevel}) {
          const double s = volume_->levels[std::size_t(l)].grid.spacing;
          for (int n = -2; n < 2; ++n)
            probeStep = std::max(probeStep, std::abs(irradiance(*volume_, at + Vector3d(0, n * s, 0), normal) -
                                                     irradiance(*volume_, at + Vector3d(0, (n + 1) * s, 0), normal)));
        }
        const double jump = std::abs(e - previous);
        EXPECT_LE(jump, probeStep) << "x " << x << " y " << y << ": level " << previousLevel << " → " << level;
        // Continuity: the level change found to within a few float steps, and E on either side of it.
        Vector3d below(x, y - step, 3.7), above(x, y, 3.7);
        for (int halving = 0; halving < 40; ++halving) {
          const Vector3d middle = 0.5 * (below + above);
          (finestLevelAt(volume_->levels, 3, middle).level == previousLevel ? below : above) = middle;
        }
        const double across = std::abs(irradiance(*volume_, above, normal) - irradiance(*volume_, below, normal));
        EXPECT_LE(across, 1e-5 * std::abs(e)) << "x " << x << " y " << below.y() << ": level " << previousLevel
                                              << " → " << level << ", E " << e;
      }
      previousLevel = level;
      previous = e;
    }
  }
  EXPECT_GE(crossings, 6) << "the lines must cross from the finest level to the coarsest and back";
}

// The C++ header decoder, given each level's grid and which sub-bricks it holds, picks the level the
// library picks and decodes the same irradiance.
TEST_F(AdaptiveBake, HeaderDecoderPicksTheFinestLevelAsTheLibraryDoes) {
  std::vector<std::vector<unsigned char>> held;
  std::vector<baker_decode::Level> levels;
  for (const Volume& level : volume_->levels) {
    const ProbeGrid& g = level.grid;
    held.emplace_back(std::size_t(g.brickCount()));
    for (std::int64_t b = 0; b < g.brickCount(); ++b) held.back()[std::size_t(b)] = level.rows.subBricks(g, b);
    levels.push_back({{g.origin.x(), g.origin.y(), g.origin.z()}, g.spacing, {g.dims.x(), g.dims.y(), g.dims.z()},
                      held.back().data()});
  }
  const baker_decode::BasisDecoder decoder("sh-l2");
  const std::vector<float> zeros(27, 0.0f);
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const Eigen::Vector3d lo = scene_->bounds.min().cast<double>(), size = scene_->bounds.sizes().cast<double>();
  int finest = 0;
  for (int n = 0; n < 2000; ++n) {
    // Most points low down, where the finest level is.
    const Vector3d at = lo + Vector3d(unit(random), std::pow(unit(random), 3.0), unit(random)).cwiseProduct(size);
    const baker_decode::LevelNeighbourhood picked = baker_decode::finestLevelNeighbourhood({at.x(), at.y(), at.z()},
                                                                                             levels.data(), 3);
    ASSERT_EQ(picked.level, finestLevelAt(volume_->levels, 3, at).level) << at.transpose();
    finest += picked.level == 2;
    const Volume& level = volume_->levels[std::size_t(picked.level)];
    const float* probes[8];
    for (int c = 0; c < 8; ++c) {
      const std::int64_t row = level.rows.row(level.grid, picked.around.probe[c]);
      probes[c] = row >= 0 ? level.coefficients.data() + row * 27 : zeros.data();
    }
    float blended[27];
    baker_decode::blendProbes(probes, picked.around.weight, 27, blended);
    const baker_decode::Rgb e = decoder.irradiance(blended, {0.0, 1.0, 0.0});
    const double expected = irradiance(*volume_, at, Vector3d::UnitY());
    EXPECT_NEAR((e.r + e.g + e.b) / 3.0, expected, 1e-5 * std::abs(expected) + 1e-6) << at.transpose();
  }
  EXPECT_GT(finest, 100);
}

TEST_F(AdaptiveBake, SameBitsOnAnyThreadCount) {
  for (const int threads : {1, 2}) {
    BakeStats stats;
    const AdaptiveVolume other = test::onThreads(
        threads, [&] { return bakeAdaptive(*scene_, *tracer_, *basis_, *placement_, settings_, &stats); });
    ASSERT_EQ(other.levels.size(), volume_->levels.size());
    for (std::size_t l = 0; l < other.levels.size(); ++l) {
      EXPECT_EQ(other.levels[l].coefficients, volume_->levels[l].coefficients) << threads << " threads, level " << l;
      EXPECT_EQ(other.levels[l].visibility, volume_->levels[l].visibility) << threads << " threads, level " << l;
      EXPECT_EQ(other.levels[l].states, volume_->levels[l].states) << threads << " threads, level " << l;
    }
    EXPECT_EQ(stats.rays.total(), stats_.rays.total());
  }
}

TEST_F(AdaptiveBake, VdbHoldsEveryLevel) {
  const std::string dir = test::makeTempDir("AdaptiveVdb");
  const std::string path = dir + "/levels.vdb";
  writeAdaptiveVdb(*volume_, *basis_, path);
  const AdaptiveVolume read = readAdaptiveVdb(path);
  ASSERT_EQ(read.levels.size(), 3u);
  EXPECT_EQ(read.marginCells, 1);
  for (std::size_t l = 0; l < 3; ++l) {
    const Volume& a = volume_->levels[l];
    const Volume& b = read.levels[l];
    EXPECT_EQ(a.grid.dims, b.grid.dims);
    EXPECT_EQ(a.grid.origin, b.grid.origin);
    EXPECT_EQ(a.grid.spacing, b.grid.spacing);
    EXPECT_EQ(a.rows.bricks(), b.rows.bricks()) << "level " << l;
    EXPECT_EQ(a.rows.masks(a.grid), b.rows.masks(b.grid)) << "level " << l;
    EXPECT_EQ(a.coefficients, b.coefficients) << "level " << l;
    EXPECT_EQ(a.visibility, b.visibility) << "level " << l;
    EXPECT_EQ(a.states, b.states) << "level " << l;
  }
  for (const Vector3d& at : {Vector3d(3.3, 0.4, -7.1), Vector3d(-20, 12, 20), Vector3d(0.5, 59.5, 0.5)})
    EXPECT_EQ(irradiance(read, at, Vector3d::UnitY()), irradiance(*volume_, at, Vector3d::UnitY()));
  // The same volume gives the same bytes.
  const std::string again = dir + "/again.vdb";
  writeAdaptiveVdb(read, *basis_, again);
  std::ifstream first(path, std::ios::binary), second(again, std::ios::binary);
  EXPECT_TRUE(std::equal(std::istreambuf_iterator<char>(first), {}, std::istreambuf_iterator<char>(second), {}));
  // A reader of one level refuses it rather than reading its coarsest level as the whole.
  try {
    readVdb(path);
    ADD_FAILURE() << "an adaptive volume was read as a uniform one";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("adaptive volume of 3 levels"), std::string::npos) << e.what();
  }
}

// Each level as its own EXR slice set, its bricks packed in an atlas: float slices read back
// exactly, half ones within half's rounding; the same bytes again; uniform readers refuse it.
TEST_F(AdaptiveBake, ExrSlicesHoldEveryLevel) {
  const std::string dir = test::makeTempDir("AdaptiveExr");
  writeAdaptiveExrSlices(*volume_, *basis_, dir + "/float", ExrPrecision::Float);
  writeAdaptiveExrSlices(*volume_, *basis_, dir + "/half", ExrPrecision::Half);
  const AdaptiveVolume read = readLevels(dir + "/float");
  const AdaptiveVolume half = readLevels(dir + "/half/manifest.json");
  ASSERT_EQ(read.levels.size(), 3u);
  ASSERT_EQ(half.levels.size(), 3u);
  EXPECT_EQ(read.marginCells, 1);
  for (std::size_t l = 0; l < 3; ++l) {
    const Volume& a = volume_->levels[l];
    for (const Volume* b : {&read.levels[l], &half.levels[l]}) {
      EXPECT_EQ(a.grid.dims, b->grid.dims);
      EXPECT_EQ(a.grid.origin, b->grid.origin);
      EXPECT_EQ(a.grid.spacing, b->grid.spacing);
      EXPECT_EQ(a.rows.bricks(), b->rows.bricks()) << "level " << l;
      EXPECT_EQ(a.states, b->states) << "level " << l;
    }
    EXPECT_EQ(a.coefficients, read.levels[l].coefficients) << "level " << l;
    EXPECT_EQ(a.visibility, read.levels[l].visibility) << "level " << l;
    for (std::size_t i = 0; i < a.coefficients.size(); ++i)
      ASSERT_NEAR(half.levels[l].coefficients[i], a.coefficients[i], std::abs(a.coefficients[i]) / 1024.0 + 1e-6);
  }
  for (const Vector3d& at : {Vector3d(3.3, 0.4, -7.1), Vector3d(-20, 12, 20), Vector3d(0.5, 59.5, 0.5)})
    EXPECT_EQ(irradiance(read, at, Vector3d::UnitY()), irradiance(*volume_, at, Vector3d::UnitY()));
  writeAdaptiveExrSlices(read, *basis_, dir + "/again", ExrPrecision::Float);
  for (const auto& entry : std::filesystem::recursive_directory_iterator(dir + "/float")) {
    if (!entry.is_regular_file()) continue;
    const std::string relative = std::filesystem::relative(entry.path(), dir + "/float").string();
    std::ifstream first(entry.path(), std::ios::binary), second(dir + "/again/" + relative, std::ios::binary);
    ASSERT_TRUE(second) << relative;
    EXPECT_TRUE(std::equal(std::istreambuf_iterator<char>(first), {}, std::istreambuf_iterator<char>(second), {})) << relative;
  }
  const auto refused = [&](const std::string& path, const std::string& needle) {
    try {
      readVolume(path);
      ADD_FAILURE() << path << " was read as a uniform volume";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
  };
  refused(dir + "/float", "an adaptive volume of 3 levels");
  refused(dir + "/float/level1", "one level of an adaptive volume");
}

// A level's atlas that lies: bricks out of order, the wrong slot counts, or a value where the
// atlas holds no probe.
TEST_F(AdaptiveBake, ExrLevelDamageIsRefused) {
  const std::string dir = test::makeTempDir("AdaptiveExrDamage");
  const auto damaged = [&](const std::string& name, const std::function<void(nlohmann::json&)>& change,
                           const std::string& needle) {
    const std::string path = dir + "/" + name;
    writeAdaptiveExrSlices(*volume_, *basis_, path, ExrPrecision::Float);
    const std::string manifestPath = path + "/level2/manifest.json";
    nlohmann::json m = nlohmann::json::parse(std::ifstream(manifestPath));
    change(m);
    std::ofstream(manifestPath) << m.dump();
    try {
      readLevels(path);
      ADD_FAILURE() << name << " was read";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << name << ": " << e.what();
    }
  };
  damaged("order", [](nlohmann::json& m) { std::swap(m["atlas"]["bricks"][0], m["atlas"]["bricks"][1]); },
          "must be in increasing order");
  damaged("slots", [](nlohmann::json& m) { m["atlas"]["slots"][2] = 400; }, "\"atlas\".\"slots\" must be");
  damaged("outside", [&](nlohmann::json& m) { m["atlas"]["bricks"].back() = volume_->levels[2].grid.brickCount(); },
          "a brick of a level lies outside");
  damaged("nest", [](nlohmann::json& m) { m["origin"][0] = m["origin"][0].get<double>() + 0.1; }, "do not nest in level 1");
}

// The bake keeps of each level only the bricks a file keeps (volume/StoredBricks.h), before finer
// levels read it.
TEST_F(AdaptiveBake, EveryHeldBrickIsWorthStoring) {
  for (std::size_t l = 0; l < volume_->levels.size(); ++l) {
    const Volume& level = volume_->levels[l];
    const std::vector<bool> worth = bricksWorthStoring(level);
    for (std::int64_t b = 0; b < level.grid.brickCount(); ++b)
      EXPECT_EQ(worth[std::size_t(b)], level.rows.holdsBrick(b)) << "level " << l << " brick " << b;
  }
}

// A level holding sub-bricks of a brick: only their probes have rows, each probe one row and
// back; a kept brick keeps its sub-bricks and its probes' values.
TEST(StoredBricks, SubBricksHoldOnlyTheirProbes) {
  Volume v;
  v.grid.dims = {12, 8, 8};  // bricks 0 (8 wide) and 1 (4 wide: sub-bricks 0, 2, 4, 6 only)
  v.coefficientsPerProbe = 1;
  const std::uint8_t lowerX = 0x55, upperY = 0xCC;  // sub-bricks with sx = 0; with sy = 1
  v.rows = ProbeRows(v.grid, {1, 0}, {kEverySubBrick, upperY});
  EXPECT_TRUE(v.rows.holdsPartialBricks());
  EXPECT_EQ(v.rows.subBricks(v.grid, 1), lowerX) << "kept within the sub-bricks the grid has";
  EXPECT_EQ(v.rows.row(v.grid, 0, 0, 0), -1);
  EXPECT_EQ(v.rows.probesHeld(v.grid, 0), 8 * 4 * 8);
  EXPECT_EQ(v.rows.count(v.grid), 8 * 4 * 8 + 4 * 8 * 8) << "a row per probe held";
  std::vector<bool> seen(std::size_t(v.rows.count(v.grid)), false);
  for (int k = 0; k < 8; ++k)
    for (int j = 0; j < 8; ++j)
      for (int i = 0; i < 12; ++i) {
        const std::int64_t row = v.rows.row(v.grid, i, j, k);
        ASSERT_EQ(row >= 0, i >= 8 || j >= 4) << i << " " << j << " " << k;
        if (row < 0) continue;
        ASSERT_LT(row, v.rows.count(v.grid));
        EXPECT_FALSE(seen[std::size_t(row)]) << "row " << row << " twice";
        seen[std::size_t(row)] = true;
        EXPECT_EQ(v.rows.probeAt(v.grid, row), v.grid.linearIndex(i, j, k));
      }
  v.coefficients.resize(std::size_t(v.rows.count(v.grid)));
  v.states.assign(std::size_t(v.rows.count(v.grid)), ProbeState::Valid);
  for (std::int64_t r = 0; r < v.rows.count(v.grid); ++r) v.coefficients[std::size_t(r)] = float(v.rows.probeAt(v.grid, r));
  const Volume kept = keepBricks(v, {true, false});
  EXPECT_EQ(kept.rows.bricks(), (std::vector<std::int64_t>{0}));
  EXPECT_EQ(kept.rows.subBricks(kept.grid, 0), upperY);
  EXPECT_EQ(kept.coefficients.size(), std::size_t(8 * 4 * 8));
  for (int k = 0; k < 8; ++k)
    for (int j = 4; j < 8; ++j)
      for (int i = 0; i < 8; ++i)
        EXPECT_EQ(kept.coefficients[std::size_t(kept.rows.row(kept.grid, i, j, k))], float(kept.grid.linearIndex(i, j, k)));
}

// Bricks 0, 2 and 3 of a 4-brick row held (in the order 3, 0, 2), brick 3 dropped: every probe
// kept has its values and state, brick 3's are not held.
TEST(StoredBricks, KeepBricksKeepsEachProbesValues) {
  Volume v;
  v.grid.dims = {32, 5, 3};
  v.grid.spacing = 1.0;
  v.rows = ProbeRows(v.grid, {3, 0, 2});
  v.coefficientsPerProbe = 2;
  v.visibilityPerProbe = 1;
  const std::int64_t rows = v.rows.count(v.grid);
  for (std::int64_t r = 0; r < rows; ++r) {
    v.coefficients.insert(v.coefficients.end(), {float(r), float(-r)});
    v.visibility.push_back(float(r) / 2.0f);
    v.states.push_back(ProbeState(r % 3));
    v.offsets.push_back(Eigen::Vector3f(float(r), 0.0f, 1.0f));
  }
  const Volume kept = keepBricks(v, {true, true, true, false});
  EXPECT_EQ(kept.rows.bricks(), (std::vector<std::int64_t>{0, 2}));
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 5; ++j)
      for (int i = 0; i < 32; ++i) {
        const std::int64_t from = v.rows.row(v.grid, i, j, k), to = kept.rows.row(kept.grid, i, j, k);
        if (i < 8 || (i >= 16 && i < 24)) {
          ASSERT_GE(to, 0);
          EXPECT_EQ(kept.coefficients[std::size_t(2 * to + 1)], v.coefficients[std::size_t(2 * from + 1)]);
          EXPECT_EQ(kept.visibility[std::size_t(to)], v.visibility[std::size_t(from)]);
          EXPECT_EQ(kept.states[std::size_t(to)], v.states[std::size_t(from)]);
          EXPECT_EQ(kept.offsets[std::size_t(to)], v.offsets[std::size_t(from)]);
        } else {
          EXPECT_EQ(to, -1);
        }
      }
  EXPECT_EQ(kept.coefficients.size(), std::size_t(2 * 2 * 8 * 5 * 3));

  // A volume holding every probe (rows in grid order) keeps its bricks' probes the same way.
  Volume whole = v;
  whole.rows = ProbeRows();
  const std::int64_t probes = whole.grid.probeCount();
  whole.coefficients.resize(std::size_t(2 * probes));
  whole.visibility.resize(std::size_t(probes));
  whole.states.resize(std::size_t(probes));
  whole.offsets.resize(std::size_t(probes));
  for (std::int64_t p = 0; p < probes; ++p) whole.coefficients[std::size_t(2 * p)] = float(p);
  const Volume some = keepBricks(whole, {false, true, false, true});
  EXPECT_EQ(some.rows.bricks(), (std::vector<std::int64_t>{1, 3}));
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 5; ++j)
      for (int i = 0; i < 32; ++i) {
        const std::int64_t to = some.rows.row(some.grid, i, j, k);
        if ((i >= 8 && i < 16) || i >= 24)
          EXPECT_EQ(some.coefficients[std::size_t(2 * to)], float(whole.grid.linearIndex(i, j, k)));
        else
          EXPECT_EQ(to, -1);
      }
}

// A solid cube 40 m wide: the bricks of level 0 deep inside it are not placed.
TEST(AdaptivePlacement, NothingDeepInsideClosedGeometry) {
  test::GltfBuilder gltf;
  std::vector<float> corners;
  for (int c = 0; c < 8; ++c) corners.insert(corners.end(), {c & 1 ? 20.f : -20.f, c & 2 ? 20.f : -20.f, c & 4 ? 20.f : -20.f});
  // Outward-facing (counter-clockwise seen from outside) faces of the cube.
  const std::vector<std::uint32_t> faces = {0, 2, 3, 0, 3, 1, 4, 5, 7, 4, 7, 6, 0, 1, 5, 0, 5, 4,
                                            2, 6, 7, 2, 7, 3, 0, 4, 6, 0, 6, 2, 1, 3, 7, 1, 7, 5};
  gltf.node({{"mesh", gltf.mesh({{"POSITION", gltf.floats(corners, "VEC3")}}, gltf.indices(faces))}});
  const Scene scene = loadGltf(gltf.write(test::makeTempDir("SolidCube"), "cube"));
  const RayTracer tracer(scene);
  const ProbeGrid coarsest = makeProbeGrid(scene.bounds, 1.0, 1 << 20);  // 40³ probes, 5³ bricks
  const AdaptivePlacement p = placeAdaptive(scene, tracer, coarsest, 1, 1, 1 << 20);
  EXPECT_EQ(p.deepInsideBricks, 27) << "the 3³ bricks that no face comes within a cell of";
  EXPECT_EQ(p.bricks[0].size(), 125u - 27u);
}

// A solid slab 24 m wide and deep, a small box sunk in the middle of it, and a panel 8 m above
// (so that the grid has air over the slab). The sunk box places a brick of the finer level whose
// probes, and their neighbours, all lie inside the slab: the bake drops it, and keeps every brick
// with a probe in the air or next to one.
TEST(AdaptiveBakeDrops, BricksInsideGeometryAwayFromAir) {
  test::GltfBuilder gltf;
  const std::vector<std::uint32_t> faces = {0, 2, 3, 0, 3, 1, 4, 5, 7, 4, 7, 6, 0, 1, 5, 0, 5, 4,
                                            2, 6, 7, 2, 7, 3, 0, 4, 6, 0, 6, 2, 1, 3, 7, 1, 7, 5};
  const auto box = [&](Vector3d lo, Vector3d hi) {
    std::vector<float> corners;
    for (int c = 0; c < 8; ++c)
      corners.insert(corners.end(), {float(c & 1 ? hi.x() : lo.x()), float(c & 2 ? hi.y() : lo.y()),
                                     float(c & 4 ? hi.z() : lo.z())});
    gltf.node({{"mesh", gltf.mesh({{"POSITION", gltf.floats(corners, "VEC3")}}, gltf.indices(faces))}});
  };
  box({-12, -24, -12}, {12, 0, 12});
  box({-1, -13, -1}, {1, -11, 1});
  gltf.node({{"mesh", gltf.mesh({{"POSITION", gltf.floats({0, 8, 0, 1, 8, 0, 1, 8, 1, 0, 8, 1}, "VEC3")}},
                                gltf.indices({0, 1, 2, 0, 2, 3}))}});
  const Scene scene = loadGltf(gltf.write(test::makeTempDir("SunkBox"), "slab"));
  const RayTracer tracer(scene);
  const std::unique_ptr<Basis> basis = makeBasis("sh-l1");
  const AdaptivePlacement placement = placeAdaptive(scene, tracer, makeProbeGrid(scene.bounds, 1.0, 1 << 20), 2, 1, 1 << 20);
  BakeSettings settings;
  settings.rays = 16;
  settings.transport.probeValidity = true;
  const AdaptiveVolume volume = bakeAdaptive(scene, tracer, *basis, placement, settings, nullptr);
  const Volume& fine = volume.levels[1];
  const ProbeGrid& g = fine.grid;
  const Vector3d sunk = (Vector3d(0, -12, 0) - g.origin) / g.spacing;
  const std::int64_t sunkBrick = g.brickOf(int(sunk.x()), int(sunk.y()), int(sunk.z()));
  const std::vector<std::int64_t>& placed = placement.bricks[1];
  ASSERT_TRUE(std::binary_search(placed.begin(), placed.end(), sunkBrick)) << "the sunk box places its brick";
  EXPECT_FALSE(fine.rows.holdsBrick(sunkBrick)) << "a brick inside the slab, away from air, is dropped";
  EXPECT_LT(fine.rows.bricks().size(), placed.size());
  for (std::size_t l = 0; l < volume.levels.size(); ++l) {
    const std::vector<bool> worth = bricksWorthStoring(volume.levels[l]);
    for (std::int64_t b = 0; b < volume.levels[l].grid.brickCount(); ++b)
      EXPECT_EQ(worth[std::size_t(b)], volume.levels[l].rows.holdsBrick(b)) << "level " << l << " brick " << b;
  }
  // Above the slab the finer level still covers the surface; the files hold what the bake holds.
  const std::string dir = test::makeTempDir("SunkBoxFiles");
  writeAdaptiveVdb(volume, *basis, dir + "/v.vdb");
  writeAdaptiveExrSlices(volume, *basis, dir + "/v_exr", ExrPrecision::Float);
  for (const std::string& path : {dir + "/v.vdb", dir + "/v_exr"}) {
    const AdaptiveVolume read = readLevels(path);
    for (std::size_t l = 0; l < volume.levels.size(); ++l) {
      EXPECT_EQ(read.levels[l].rows.bricks(), volume.levels[l].rows.bricks()) << path << " level " << l;
      EXPECT_EQ(read.levels[l].rows.masks(read.levels[l].grid), volume.levels[l].rows.masks(volume.levels[l].grid))
          << path << " level " << l;
      EXPECT_EQ(read.levels[l].coefficients, volume.levels[l].coefficients) << path << " level " << l;
    }
  }
}

TEST(AdaptiveBadInput, ClearMessagesAndExitCode2) {
  const std::string dir = test::makeTempDir("AdaptiveBadInput");
  const std::string scene = test::sourcePath("data/default_room/default_room.gltf");
  const auto rejected = [&](const std::vector<std::string>& args, const std::string& needle) {
    std::vector<std::string> all{scene};
    all.insert(all.end(), args.begin(), args.end());
    const test::ProcessResult run = test::runBaker(dir, all);
    EXPECT_EQ(run.exitCode, 2) << run.err;
    EXPECT_NE(run.err.find(needle), std::string::npos) << run.err;
  };
  rejected({"--placement", "adaptive", "--levels", "0"}, "--levels must be in 1..4, got 0");
  rejected({"--placement", "adaptive", "--levels", "5"}, "--levels must be in 1..4, got 5");
  rejected({"--placement", "adaptive", "--margin", "5"}, "--margin must be in 1..4 cells, got 5");
  rejected({"--placement", "adaptive", "--margin", "0"}, "--margin must be in 1..4 cells, got 0");
  rejected({"--placement", "sparse"}, "--placement must be uniform or adaptive");
  rejected({"--levels", "2"}, "--levels applies to --placement adaptive only");
  rejected({"--placement", "adaptive", "--format", "bevy", "--out", "x_bevy"}, "levels are written to a .vdb file or EXR slices only");
  rejected({"--placement", "adaptive", "--levels", "1", "--shard", "0/2"}, "an adaptive bake of one level");
  rejected({"--placement", "adaptive", "--shard", "0/2", "--format", "exr"}, "a shard's part of an adaptive bake is a .vdb file");
  EXPECT_FALSE(std::filesystem::exists(dir + "/x_bevy"));

  const test::ProcessResult bake =
      test::runBaker(dir, {scene, "--placement", "adaptive", "--levels", "2", "--rays", "8", "--out", "a.vdb", "--quiet"});
  ASSERT_EQ(bake.exitCode, 0) << bake.err;
  const test::ProcessResult sample = test::runBaker(dir, {"sample", "a.vdb", "--at", "0,1,0", "--normal", "0,1,0", "--json"});
  EXPECT_EQ(sample.exitCode, 0) << sample.err;
  EXPECT_NE(sample.out.find("\"level\": 1"), std::string::npos) << sample.out;
}

}  // namespace
}  // namespace baker
