// `baker env --signal radiance` (validate/SpecularOnEnvironment.h): its exact references against
// skies whose integrals are known, a constant sky read back exactly, and the command's output
// and refusals.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "basis/BasisRegistry.h"
#include "images/RgbImage.h"
#include "tests/BakerProcess.h"
#include "tests/TestData.h"
#include "validate/SpecularOnEnvironment.h"

namespace baker {
namespace {

constexpr int kWidth = 256, kHeight = 128;

// 1 where `lit` holds at the texel centre, 0 elsewhere.
template <typename F>
LatLongEnvironment skyWhere(const F& lit) {
  const LatLongEnvironment layout(kWidth, kHeight, Eigen::MatrixX3d::Zero(kWidth * kHeight, 3));
  Eigen::MatrixX3d values(kWidth * kHeight, 3);
  for (int row = 0; row < kHeight; ++row)
    for (int column = 0; column < kWidth; ++column)
      values.row(row * kWidth + column).setConstant(lit(layout.direction(row, column)) ? 1.0 : 0.0);
  return LatLongEnvironment(kWidth, kHeight, values);
}

// Half of the sky lit, along each axis in turn: a normal into the lit half sees E = π and, for a
// lobe about it, S = 1; one into the dark half sees 0. A mirrored or turned lookup fails here.
TEST(EnvironmentSpecular, ReferencesSeeTheSkyWhereItIs) {
  for (int axis = 0; axis < 3; ++axis) {
    const LatLongEnvironment sky = skyWhere([axis](const Eigen::Vector3d& d) { return d[axis] > 0.0; });
    const Eigen::Vector3d lit = Eigen::Vector3d::Unit(axis);
    // The texels' centres stand for their patches: π within the texel size squared.
    EXPECT_NEAR(exactIrradianceAt(sky, lit).x(), M_PI, 2e-3 * M_PI) << "axis " << axis;
    EXPECT_NEAR(exactIrradianceAt(sky, -lit).x(), 0.0, 2e-3 * M_PI) << "axis " << axis;
    for (double roughness : {0.1, 0.3, 1.0}) {
      EXPECT_NEAR(exactSpecularAt(sky, {lit, lit}, roughness).x(), 1.0, 1e-3) << "axis " << axis << " r " << roughness;
      EXPECT_NEAR(exactSpecularAt(sky, {-lit, -lit}, roughness).x(), 0.0, 1e-3) << "axis " << axis << " r " << roughness;
    }
  }
  // A grazing lobe over the boundary: symmetric about it, so half lit.
  const LatLongEnvironment upper = skyWhere([](const Eigen::Vector3d& d) { return d.y() > 0.0; });
  EXPECT_NEAR(exactSpecularAt(upper, {Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitX()}, 0.3).x(), 0.5, 0.02);
}

TEST(EnvironmentSpecular, AConstantSkyIsReadExactly) {
  const LatLongEnvironment sky(kWidth, kHeight, Eigen::MatrixX3d::Constant(kWidth * kHeight, 3, 0.7));
  for (const std::string& name : {"sh-l2", "ad-srbf"}) {
    const auto scores = scoreSpecularOnEnvironment(*makeBasis(name), sky, "constant", {0.1, 0.3, 0.6, 1.0}, specularFrames());
    ASSERT_FALSE(scores.empty()) << name;
    for (const EnvironmentSpecularScore& s : scores) {
      EXPECT_LT(s.diffuseRelativeRmse, 1e-4) << name << " " << fitMethodName(s.fit);
      ASSERT_EQ(s.specularRelativeRmse.size(), 4u);
      for (const std::optional<double>& e : s.specularRelativeRmse) {
        ASSERT_TRUE(e.has_value()) << name;
        EXPECT_LT(*e, 1e-4) << name << " " << fitMethodName(s.fit);
      }
    }
  }
}

TEST(EnvironmentSpecular, CommandReportsJsonAndRefusesBadInput) {
  const std::string dir = test::makeTempDir("EnvironmentSpecularCommand");
  RgbImage image(kWidth, kHeight);
  for (int row = 0; row < kHeight; ++row)
    for (int column = 0; column < kWidth; ++column) std::fill_n(image.pixel(row, column), 3, row < 40 ? 2.0f : 0.25f);
  writeExr(image, dir + "/sky.exr");
  const test::ProcessResult run = test::runBaker(dir, "env sky.exr --basis ad-srbf --signal radiance --json");
  ASSERT_EQ(run.exitCode, 0) << run.err;
  const nlohmann::json report = nlohmann::json::parse(run.out);
  EXPECT_EQ(report.at("signal"), "radiance");
  EXPECT_EQ(report.at("frames"), 48);
  EXPECT_EQ(report.at("roughness").size(), 4u);
  EXPECT_EQ(report.at("normals"), "sphere");
  for (const char* fit : {"linear", "non_negative"}) {
    const nlohmann::json& f = report.at("fits").at(fit);
    EXPECT_EQ(f.at("bytes_per_probe"), 144);
    // A sky in two flat bands: the linear fit's irradiance is close (measured 0.6 %).
    if (std::string(fit) == "linear") EXPECT_LT(f.at("diffuse_relative_rmse").get<double>(), 0.02);
    EXPECT_EQ(f.at("specular_relative_rmse").size(), 4u);
  }
  // A hemispherical basis, and any other with --upward, is read at upward surfaces only.
  for (const char* args : {"env sky.exr --basis ad-hemi9 --signal radiance --json",
                           "env sky.exr --basis sh-l2 --signal radiance --upward --json"}) {
    const test::ProcessResult up = test::runBaker(dir, args);
    ASSERT_EQ(up.exitCode, 0) << args << ": " << up.err;
    const nlohmann::json upReport = nlohmann::json::parse(up.out);
    EXPECT_EQ(upReport.at("normals"), "up") << args;
    EXPECT_EQ(upReport.at("frames"), 24) << args;
  }
  RgbImage black(kWidth, kHeight);
  writeExr(black, dir + "/black.exr");
  const test::ProcessResult dark = test::runBaker(dir, "env black.exr --basis sh-l2 --signal radiance");
  EXPECT_EQ(dark.exitCode, 2);
  EXPECT_NE(dark.err.find("black.exr"), std::string::npos) << dark.err;
  const test::ProcessResult unknown = test::runBaker(dir, "env sky.exr --basis ad-srbf --signal specular");
  EXPECT_EQ(unknown.exitCode, 2);
  EXPECT_NE(unknown.err.find("--signal"), std::string::npos) << unknown.err;
  const test::ProcessResult images = test::runBaker(dir, "env sky.exr --basis ad-srbf --signal radiance --out-dir .");
  EXPECT_EQ(images.exitCode, 2);
  EXPECT_NE(images.err.find("--out-dir"), std::string::npos) << images.err;
  RgbImage odd(200, 100);
  writeExr(odd, dir + "/odd.exr");
  const test::ProcessResult size = test::runBaker(dir, "env odd.exr --basis ad-srbf --signal radiance");
  EXPECT_EQ(size.exitCode, 2);
  EXPECT_NE(size.err.find("odd.exr"), std::string::npos) << size.err;
}

}  // namespace
}  // namespace baker
