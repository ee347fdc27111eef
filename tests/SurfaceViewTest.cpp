// Pictures of a scene's surfaces (validate/SurfaceView.h, `baker render`): the camera's points
// against the geometry worked out by hand, the traced irradiance against π L under a constant
// sky, the comparison's counts on pictures made to have them, and the shipped thin wall seen
// from its dark side, where trilinear reading leaks and leak-aware reading does not.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "bake/BakeJob.h"
#include "tests/BakerProcess.h"
#include "tests/GltfTestAssets.h"
#include "tests/TestData.h"
#include "validate/SurfaceView.h"

namespace baker {
namespace {

BakeRequest fixedRays(const std::string& scene, int rays) {
  BakeRequest request;
  request.scenePath = scene;
  request.quality.clear();
  request.rays = rays;
  request.spacing = 0.5;
  return request;
}

// Straight down from 1.25 m over the floor with a 90° field: pixel (r, c) of 9 × 9 looks along
// (−x, −1, y) with x = 2(c + ½)/9 − 1, y = 1 − 2(r + ½)/9 (right is −X, up +Z when looking
// down), so it meets the floor at eye + 1.25 (−x, −1, y). Then level, towards the wall at
// z = −2 a metre away: right is +X, up +Y, and pixel (r, c) meets it at eye + (x, y, −1).
TEST(SurfaceView, EachPixelSeesTheSurfaceWhereItsRayMeetsIt) {
  const BakeJob job(fixedRays(test::sourcePath("data/thin_walls/thin_wall_quarter.gltf"), 16));
  SurfaceCamera camera;
  camera.verticalFovDegrees = 90.0;
  camera.width = camera.height = 9;
  struct View {
    Eigen::Vector3d eye, target, normal;
    std::function<Eigen::Vector3d(double, double)> expected;
  };
  const View views[] = {
      {{-1.5, 1.25, 0.0}, {-1.5, 0.0, 0.0}, Eigen::Vector3d::UnitY(),
       [](double x, double y) { return Eigen::Vector3d(-1.5 - 1.25 * x, 0.0, 1.25 * y); }},
      {{-1.5, 1.25, -1.0}, {-1.5, 1.25, -2.0}, Eigen::Vector3d::UnitZ(),
       [](double x, double y) { return Eigen::Vector3d(-1.5 + x, 1.25 + y, -2.0); }}};
  for (const View& view : views) {
    camera.eye = view.eye;
    camera.target = view.target;
    const std::vector<SeenPoint> points = surfacesSeen(job.tracer(), camera);
    ASSERT_EQ(points.size(), 81u);
    for (int r = 0; r < 9; ++r)
      for (int c = 0; c < 9; ++c) {
        const double x = 2.0 * (c + 0.5) / 9.0 - 1.0, y = 1.0 - 2.0 * (r + 0.5) / 9.0;
        const SeenPoint& p = points[std::size_t(r) * 9 + c];
        ASSERT_TRUE(p.seen) << r << " " << c;
        EXPECT_LT((p.point - view.expected(x, y)).norm(), 1e-5) << r << " " << c;
        EXPECT_LT((p.normal - view.normal).norm(), 1e-6) << r << " " << c;
      }
  }
}

// A square alone under a constant sky: every point sees the whole upper hemisphere, so its
// irradiance is π L exactly; the probe there must find it (quadrature and the direct view's
// sky samples together) within 1 %.
TEST(SurfaceView, TracedIrradianceUnderAConstantSkyIsPiTimesTheSky) {
  const std::string dir = test::makeTempDir("SurfaceViewSky");
  test::GltfBuilder gltf;
  const int material = gltf.material({{"pbrMetallicRoughness", {{"baseColorFactor", {0.5, 0.5, 0.5, 1.0}}}}});
  gltf.node({{"mesh", test::squareMesh(gltf, 4.0f, material)}});
  BakeRequest request = fixedRays(gltf.write(dir, "square"), 256);
  request.scene.sky = "0.5,0.7,0.9";
  request.bounces = 0;
  const BakeJob job(request);
  SurfaceCamera camera;
  camera.eye = {2.0, 2.0, 2.5};
  camera.target = {2.0, 2.0, 0.0};
  camera.width = 16;
  camera.height = 12;
  const std::vector<SeenPoint> points = surfacesSeen(job.tracer(), camera);
  const std::vector<Eigen::Vector3f> traced = tracedIrradiance(job, points, 1000);
  int seen = 0;
  for (std::size_t p = 0; p < points.size(); ++p) {
    ASSERT_TRUE(points[p].seen) << p;
    ++seen;
    EXPECT_LT((points[p].normal - Eigen::Vector3d::UnitZ()).norm(), 1e-6);
    const Eigen::Vector3f expected = float(M_PI) * Eigen::Vector3f(0.5f, 0.7f, 0.9f);
    EXPECT_LT((traced[p] - expected).cwiseAbs().maxCoeff(), 0.01 * expected.maxCoeff()) << traced[p].transpose();
  }
  EXPECT_EQ(seen, 16 * 12);
}

// 10 × 4 pixels on one plane, traced 1 everywhere. Read: a step of 0.2 from column 5 on (a seam
// in each row, no leak: under a quarter), one pixel at 0.4 (below half: a blotch, not a seam, its
// two steps flanking each other), one at 1.5 (a leak).
TEST(SurfaceView, TheComparisonCountsSeamsLeaksAndBlotches) {
  const int width = 10, height = 4;
  std::vector<SeenPoint> points(width * height);
  std::vector<Eigen::Vector3f> traced(points.size(), Eigen::Vector3f::Ones()), read = traced;
  for (int r = 0; r < height; ++r)
    for (int c = 0; c < width; ++c) {
      SeenPoint& p = points[std::size_t(r) * width + c];
      p.seen = true;
      p.point = {0.01 * c, -0.01 * r, 0.0};
      if (c >= 5) read[std::size_t(r) * width + c] *= 1.2f;
    }
  read[1 * width + 2] = Eigen::Vector3f::Constant(0.4f);
  read[2 * width + 8] = Eigen::Vector3f::Constant(1.5f);
  EXPECT_DOUBLE_EQ(surfaceLevel(points, traced), 1.0);
  const SurfaceError e = compareSurfaces(points, read, traced, width, 1.0);
  // Pairs with a pixel on either side: 7 per row across, 1 per column down.
  EXPECT_EQ(e.planePairs, 7 * height + 1 * width);
  EXPECT_DOUBLE_EQ(e.seams, 4.0 / double(e.planePairs));
  EXPECT_NEAR(e.largestStep, 0.2, 1e-6);
  EXPECT_DOUBLE_EQ(e.darkBlotches, 1.0 / 40.0);
  EXPECT_DOUBLE_EQ(e.leaks, 1.0 / 40.0);
  // A smooth ramp steep enough to step 0.1 a pixel has no seam.
  std::vector<Eigen::Vector3f> ramp(points.size());
  for (std::size_t p = 0; p < points.size(); ++p) ramp[p] = Eigen::Vector3f::Constant(1.0f + 0.1f * float(p % width));
  EXPECT_EQ(compareSurfaces(points, ramp, traced, width, 1.0).seams, 0.0);
  // A pixel on another plane takes away the pairs it would be part of.
  points[0].normal = Eigen::Vector3d::UnitX();
  EXPECT_EQ(compareSurfaces(points, read, traced, width, 1.0).planePairs, e.planePairs - 2);
}

double share(const nlohmann::json& render, const char* panel, const char* key) {
  return render.at("errors").at(panel).at(key).get<double>();
}

// The wall a quarter of a spacing thick, seen from the side no light reaches: trilinear reading
// lights the wall and the floor beside it with the lit side's probes, leak-aware reading does
// not. Errors are shares of the lit side's level, measured from the lit side.
TEST(SurfaceView, RenderShowsTheThinWallsLeakAndLeakAwareReadingStopsIt) {
  const std::string dir = test::makeTempDir("SurfaceViewThinWall");
  const std::string scene = test::sourcePath("data/thin_walls/thin_wall_quarter.gltf");
  ASSERT_EQ(test::runBaker(dir, {scene, "--spacing", "0.5", "--rays", "128", "--out", "wall.vdb", "--quiet"}).exitCode,
            0);
  const auto render = [&](const std::string& eye, const std::string& lookAt, const std::vector<std::string>& extra) {
    std::vector<std::string> args = {"render", scene, "--spacing", "0.5", "--rays", "128", "--volume", "wall.vdb",
                                     "--eye=" + eye, "--look-at=" + lookAt, "--size", "48x36", "--out", "view.png",
                                     "--json", "--quiet"};
    args.insert(args.end(), extra.begin(), extra.end());
    const test::ProcessResult run = test::runBaker(dir, args);
    EXPECT_EQ(run.exitCode, 0) << run.err;
    return nlohmann::json::parse(run.out);
  };
  const nlohmann::json lit = render("-2.5,1.8,1.5", "-0.0625,1,-0.5", {});
  EXPECT_EQ(lit.at("panels"), nlohmann::json({"traced", "trilinear", "leak_aware"}));
  EXPECT_EQ(lit.at("level_from"), "traced");
  ASSERT_GT(lit.at("level").get<double>(), 0.0);
  // On the lit side both readings follow the traced picture (measured: trilinear 24 % off on
  // average, darkened by the dark probes; leak-aware 9 %), with no dark blotch.
  EXPECT_LT(share(lit, "leak_aware", "mean_error_of_level"), 0.15);
  EXPECT_GT(share(lit, "trilinear", "mean_error_of_level"), share(lit, "leak_aware", "mean_error_of_level"));
  EXPECT_EQ(share(lit, "leak_aware", "dark_blotch_share"), 0.0);
  const nlohmann::json dark = render("2.5,1.8,1.5", "0.0625,1,-0.5", {"--level", lit.at("level").dump()});
  EXPECT_EQ(dark.at("level_from"), "given");
  EXPECT_GT(share(dark, "trilinear", "leak_share"), 0.05);
  EXPECT_LT(share(dark, "leak_aware", "leak_share"), 0.005);
  EXPECT_LT(share(dark, "leak_aware", "mean_error_of_level"), 0.01);
  EXPECT_TRUE(std::filesystem::exists(dir + "/view.png"));
}

TEST(SurfaceView, RenderRefusesACameraItCannotUse) {
  const std::string dir = test::makeTempDir("SurfaceViewRefusals");
  const std::string scene = test::sourcePath("data/thin_walls/thin_wall_quarter.gltf");
  const auto refused = [&](const std::vector<std::string>& extra, const std::string& message) {
    std::vector<std::string> args = {"render", scene, "--rays", "16", "--out", "view.png"};
    args.insert(args.end(), extra.begin(), extra.end());
    const test::ProcessResult run = test::runBaker(dir, args);
    EXPECT_EQ(run.exitCode, 2) << run.err;
    EXPECT_NE(run.err.find(message), std::string::npos) << run.err;
  };
  refused({"--eye=0,1,0", "--look-at=0,1,0"}, "--look-at: the camera looks at its own --eye");
  refused({"--eye=-1,1,0", "--look-at=0,1,0", "--fov", "180"}, "--fov 180");
  refused({"--eye=-1,1,0", "--look-at=0,1,0", "--size", "64"}, "--size 64: expected WIDTHxHEIGHT");
  refused({"--eye=-1,1,0", "--look-at=0,1,0", "--size", "5x5"}, "--size 5x5");
  refused({"--eye=-1,1,0", "--look-at=0,1,0", "--level", "0"}, "--level 0");
  refused({"--eye=-1,1,0", "--look-at=0,1,0", "--volume", "missing.vdb"}, "missing.vdb");
  refused({"--eye=-1,1,0", "--look-at=0,1,0", "--size", "4096x8"}, "--size 4096x8");
  refused({"--eye=0,50,0", "--look-at=0,60,0"}, "the camera sees no surface");
  EXPECT_FALSE(std::filesystem::exists(dir + "/view.png"));
}

}  // namespace
}  // namespace baker
