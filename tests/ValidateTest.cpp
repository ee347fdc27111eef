#include <gtest/gtest.h>

#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "basis/BasisRegistry.h"
#include "formats/VdbWriter.h"
#include "tests/GltfTestAssets.h"
#include "tests/SyntheticVolumes.h"
#include "tests/TestData.h"
#include "validate/IrradianceError.h"
#include "validate/ReferencePanoramas.h"

// `baker validate`: volumes against volumes and against reference panoramas, in reconstructed
// irradiance, with the exit codes, JSON report and JUnit XML a CI job relies on.
namespace baker {
namespace {

const Eigen::Vector3i kDims(6, 4, 5);
const Eigen::Vector3d kOrigin(-1.0, 0.25, 0.5);
constexpr double kSpacing = 0.5;

std::string readText(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

void write(const Volume& v, const std::string& path) { writeVdb(v, *makeBasis(v.basisName), path); }

nlohmann::json readReport(const std::string& path) { return nlohmann::json::parse(readText(path)); }

class Validate : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = test::makeTempDir(::testing::UnitTest::GetInstance()->current_test_info()->name());
    reference_ = test::smoothVolume(kDims, kOrigin, kSpacing);
    write(reference_, dir_ + "/reference.vdb");
  }

  std::string dir_;
  Volume reference_;
};

TEST(ComparisonNormals, AreTheTwentySixCubeDirections) {
  const std::vector<Eigen::Vector3d>& normals = comparisonNormals();
  ASSERT_EQ(normals.size(), 26u);
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& n : normals) {
    EXPECT_NEAR(n.norm(), 1.0, 1e-12);
    sum += n;
  }
  EXPECT_LT(sum.norm(), 1e-12) << "symmetric under inversion";
}

TEST(RelativeErrors, DarkProbesAreMeasuredAgainstTheFloor) {
  // Probe 1 is black: its difference counts against the floor, 1e-3 × the mean level (1).
  const RelativeErrors r = relativeErrors({{0.1, 2.0, 2.1}, {0.001, 0.0, 0.001}});
  EXPECT_DOUBLE_EQ(r.floor, 1e-3);
  EXPECT_DOUBLE_EQ(r.perProbe[0], 0.05);
  EXPECT_DOUBLE_EQ(r.perProbe[1], 1.0);
  EXPECT_DOUBLE_EQ(r.max, 1.0);
  EXPECT_DOUBLE_EQ(r.mean, 0.525);
  EXPECT_DOUBLE_EQ(r.p99, 1.0);
}

TEST(ReferencePanoramas, AConstantSkyGivesPiTimesItsRadiance) {
  const RgbImage sky = test::constantPanorama(128, 64, Eigen::Vector3f(0.25f, 0.5f, 1.0f));
  double solidAngle = 0.0;
  for (int row = 0; row < 64; ++row) solidAngle += 128 * panoramaPixelSolidAngle(128, 64, row);
  EXPECT_NEAR(solidAngle, 4.0 * M_PI, 1e-12);
  for (const Eigen::Vector3d& e : panoramaIrradiance(sky, comparisonNormals())) {
    EXPECT_NEAR(e.x(), 0.25 * M_PI, 2e-3 * M_PI);
    EXPECT_NEAR(e.z(), 1.0 * M_PI, 4e-3 * M_PI);
  }
  // The convention: the image centre looks along +X, u = 0.75 along +Z, the top row is +Y.
  EXPECT_GT(panoramaDirection(128, 64, 64, 32).x(), 0.99);
  EXPECT_GT(panoramaDirection(128, 64, 96, 32).z(), 0.99);
  EXPECT_GT(panoramaDirection(128, 64, 0, 0).y(), 0.99);
}

TEST_F(Validate, IdenticalVolumesPassWithNoError) {
  const test::ProcessResult run =
      test::runBaker(dir_, "validate reference.vdb reference.vdb --report report.json --junit report.xml");
  EXPECT_EQ(run.exitCode, 0) << run.out << run.err;
  const nlohmann::json report = readReport(dir_ + "/report.json");
  EXPECT_EQ(report["max_relative_error"].get<double>(), 0.0);
  EXPECT_EQ(report["passed"].get<bool>(), true);
  EXPECT_EQ(report["probes_compared"].get<int>(), kDims.prod());
  EXPECT_EQ(report["sky_visibility_max_abs_difference"].get<double>(), 0.0);
  EXPECT_TRUE(report["metadata_differences"].empty());
  EXPECT_EQ(readText(dir_ + "/report.xml").find("<failure"), std::string::npos);
}

TEST_F(Validate, OneBrighterProbeFailsTheDefaultToleranceAndIsTheWorst) {
  Volume brighter = reference_;
  const std::int64_t p = brighter.grid.linearIndex(2, 1, 3);
  for (int c = 0; c < brighter.coefficientsPerProbe; ++c) brighter.coefficients[p * brighter.coefficientsPerProbe + c] *= 1.1f;
  write(brighter, dir_ + "/new.vdb");

  const test::ProcessResult tight = test::runBaker(dir_, "validate reference.vdb new.vdb --report report.json --junit report.xml");
  EXPECT_EQ(tight.exitCode, 1) << tight.out << tight.err;
  EXPECT_NE(tight.out.find("FAIL: irradiance within tolerance"), std::string::npos) << tight.out;
  const nlohmann::json report = readReport(dir_ + "/report.json");
  for (const char* key : {"max_relative_error", "mean_relative_error", "p99_relative_error", "tolerance", "passed",
                          "worst_probes", "validity_changes", "metadata_differences", "normals", "error_definition",
                          "floor", "probes_compared", "sky_visibility_max_abs_difference", "checks"})
    EXPECT_TRUE(report.contains(key)) << key;
  EXPECT_EQ(report["normals"].get<int>(), 26);
  EXPECT_EQ(report["tolerance"].get<double>(), 0.02);
  EXPECT_FALSE(report["passed"].get<bool>());
  const nlohmann::json& worst = report["worst_probes"][0];
  EXPECT_EQ(worst["index"], nlohmann::json({2, 1, 3}));
  const Eigen::Vector3d position = kOrigin + kSpacing * Eigen::Vector3d(2, 1, 3);
  for (int a = 0; a < 3; ++a) EXPECT_DOUBLE_EQ(worst["position"][a].get<double>(), position[a]);
  // E scales by 1.1 everywhere, so the error is 0.1 × max E / mean E of that probe.
  EXPECT_GT(worst["relative_error"].get<double>(), 0.1);
  EXPECT_LT(worst["relative_error"].get<double>(), 0.2);
  EXPECT_EQ(report["worst_probes"].size(), 10u);
  EXPECT_EQ(report["worst_probes"][1]["relative_error"].get<double>(), 0.0);
  EXPECT_LT(report["mean_relative_error"].get<double>(), worst["relative_error"].get<double>() / 100);

  const std::string xml = readText(dir_ + "/report.xml");
  EXPECT_NE(xml.find("<testsuite name=\"baker validate\""), std::string::npos) << xml;
  EXPECT_NE(xml.find("<testcase classname=\"baker validate\" name=\"irradiance within tolerance\""), std::string::npos);
  EXPECT_NE(xml.find("<testcase classname=\"baker validate\" name=\"validity unchanged\""), std::string::npos);
  EXPECT_NE(xml.find("<testcase classname=\"baker validate\" name=\"metadata\""), std::string::npos);
  EXPECT_NE(xml.find("<failure message=\"max relative error"), std::string::npos) << xml;
  EXPECT_NE(xml.find("failures=\"1\""), std::string::npos) << xml;
  EXPECT_NE(xml.find("</testsuite>"), std::string::npos);

  const test::ProcessResult loose = test::runBaker(dir_, "validate reference.vdb new.vdb --tolerance 0.2 --json");
  EXPECT_EQ(loose.exitCode, 0) << loose.out << loose.err;
  EXPECT_TRUE(nlohmann::json::parse(loose.out)["passed"].get<bool>());
}

TEST_F(Validate, ChangedValidityIsReportedAndFails) {
  Volume changed = reference_;
  changed.states[changed.grid.linearIndex(4, 2, 1)] = ProbeState::Invalid;
  changed.states[changed.grid.linearIndex(0, 0, 0)] = ProbeState::Relocated;
  write(changed, dir_ + "/new.vdb");
  const test::ProcessResult run = test::runBaker(dir_, "validate reference.vdb new.vdb --json --junit report.xml");
  EXPECT_EQ(run.exitCode, 1) << run.out << run.err;
  const nlohmann::json report = nlohmann::json::parse(run.out);
  EXPECT_EQ(report["max_relative_error"].get<double>(), 0.0);
  ASSERT_EQ(report["validity_changes"].size(), 2u);
  EXPECT_EQ(report["validity_changes"][0]["index"], nlohmann::json({0, 0, 0}));
  EXPECT_EQ(report["validity_changes"][0]["new"], "relocated");
  EXPECT_EQ(report["validity_changes"][1]["index"], nlohmann::json({4, 2, 1}));
  EXPECT_EQ(report["validity_changes"][1]["reference"], "valid");
  EXPECT_EQ(report["validity_changes"][1]["new"], "invalid");
  const std::string xml = readText(dir_ + "/report.xml");
  EXPECT_NE(xml.find("<failure message=\"2 probe(s) changed probe_state\""), std::string::npos) << xml;
  EXPECT_NE(xml.find("probe [4, 2, 1]"), std::string::npos) << xml;
}

TEST_F(Validate, ADifferentGridIsSampledAtTheReferenceProbes) {
  // The same affine field on a finer grid covering only part of the reference's probes.
  Volume finer = test::smoothVolume({7, 5, 3}, kOrigin + Eigen::Vector3d(0.25, 0.0, 0.5), 0.25);
  finer.settings["rays"] = "1024";
  write(finer, dir_ + "/finer.vdb");
  const test::ProcessResult run = test::runBaker(dir_, "validate reference.vdb finer.vdb --json");
  EXPECT_EQ(run.exitCode, 0) << run.out << run.err;
  const nlohmann::json report = nlohmann::json::parse(run.out);
  EXPECT_FALSE(report["grids_match"].get<bool>());
  EXPECT_LT(report["max_relative_error"].get<double>(), 1e-5);
  EXPECT_LT(report["sky_visibility_max_abs_difference"].get<double>(), 1e-5);
  EXPECT_GT(report["probes_compared"].get<int>(), 0);
  EXPECT_GT(report["probes_outside_new_grid"].get<int>(), 0);
  EXPECT_EQ(report["probes_compared"].get<int>() + report["probes_outside_new_grid"].get<int>(), kDims.prod());
  EXPECT_FALSE(report["validity_compared"].get<bool>());
  std::set<std::string> fields;
  for (const nlohmann::json& d : report["metadata_differences"]) fields.insert(d["field"].get<std::string>());
  EXPECT_EQ(fields, (std::set<std::string>{"dims", "origin", "spacing", "setting.rays"}));
}

TEST_F(Validate, UnusableInputExitsWithTwo) {
  const test::ProcessResult missing = test::runBaker(dir_, "validate reference.vdb missing.vdb");
  EXPECT_EQ(missing.exitCode, 2);
  EXPECT_NE(missing.err.find("missing.vdb"), std::string::npos) << missing.err;

  write(test::smoothVolume({2, 2, 2}, Eigen::Vector3d(50, 50, 50), 0.5), dir_ + "/far.vdb");
  const test::ProcessResult far = test::runBaker(dir_, "validate reference.vdb far.vdb --report report.json");
  EXPECT_EQ(far.exitCode, 2);
  EXPECT_NE(far.err.find("does not overlap"), std::string::npos) << far.err;
  EXPECT_FALSE(std::filesystem::exists(dir_ + "/report.json"));

  EXPECT_EQ(test::runBaker(dir_, "validate reference.vdb").exitCode, 2);
  EXPECT_EQ(test::runBaker(dir_, "validate reference.vdb reference.vdb --tolerance -1").exitCode, 2);
  EXPECT_EQ(test::runBaker(dir_, "validate reference.vdb --against-reference nowhere").exitCode, 2);
}

// A ground plane under a uniform sky, baked in two bases: the same light, differently represented.
TEST(ValidateBakes, TwoBasesOfTheSameBakeAgree) {
  const std::string dir = test::makeTempDir("validate_bases");
  test::GltfBuilder gltf;
  const int material = gltf.material({{"pbrMetallicRoughness", {{"baseColorFactor", {0.6, 0.5, 0.4, 1.0}}}}});
  gltf.node({{"mesh", test::squareMesh(gltf, 4.0f, material)}, {"rotation", {-0.7071068, 0.0, 0.0, 0.7071068}}});
  gltf.write(dir, "ground");
  for (const char* basis : {"sh-l2", "ad-rgb"}) {
    const test::ProcessResult bake =
        test::runBaker(dir, fmt::format("ground.gltf --basis {} --spacing 1 --rays 256 --bounces 1 --sky 1,1,1 --out {}.vdb --quiet",
                                        basis, basis));
    ASSERT_EQ(bake.exitCode, 0) << bake.err;
  }
  const test::ProcessResult run = test::runBaker(dir, "validate sh-l2.vdb ad-rgb.vdb --tolerance 0.1 --json");
  EXPECT_EQ(run.exitCode, 0) << run.out << run.err;
  const nlohmann::json report = nlohmann::json::parse(run.out);
  EXPECT_TRUE(report["grids_match"].get<bool>());
  EXPECT_LT(report["max_relative_error"].get<double>(), 0.1);
  EXPECT_GT(report["max_relative_error"].get<double>(), 0.0);
  EXPECT_TRUE(report["validity_changes"].empty());
  ASSERT_FALSE(report["metadata_differences"].empty());
  EXPECT_EQ(report["metadata_differences"][0]["field"], "basis");
}

// Against a reference directory written here: a sky of constant radiance L gives E(n) = πL, which
// a bake of an empty scene under --sky L reproduces.
TEST(ValidateBakes, ASkyBakeMatchesConstantReferencePanoramas) {
  const std::string dir = test::makeTempDir("validate_reference");
  test::GltfBuilder gltf;
  gltf.write(dir, "empty");
  const test::ProcessResult bake =
      test::runBaker(dir, "empty.gltf --sky 0.25,0.5,1 --spacing 1 --rays 64 --no direct-punctual --out sky.vdb --quiet");
  ASSERT_EQ(bake.exitCode, 0) << bake.err;
  std::filesystem::create_directory(dir + "/ref");
  test::writeReferenceDirectory(dir + "/ref", {{0, 0, 0}, {0.25, -0.25, 0.1}, {5, 5, 5}},
                                test::constantPanorama(128, 64, Eigen::Vector3f(0.25f, 0.5f, 1.0f)), 2);

  const test::ProcessResult run =
      test::runBaker(dir, "validate sky.vdb --against-reference ref --report report.json --junit report.xml");
  EXPECT_EQ(run.exitCode, 0) << run.out << run.err;
  EXPECT_NE(run.out.find("--no direct-punctual"), std::string::npos) << run.out;
  const nlohmann::json report = readReport(dir + "/report.json");
  EXPECT_EQ(report["mode"], "reference");
  EXPECT_EQ(report["probes_compared"].get<int>(), 2);
  EXPECT_EQ(report["probes_outside_new_grid"].get<int>(), 1);
  EXPECT_LT(report["max_relative_error"].get<double>(), 0.01);
  EXPECT_EQ(report["worst_probes"].size(), 2u);
  EXPECT_TRUE(report["worst_probes"][0]["index"].is_number_integer());
  EXPECT_NE(readText(dir + "/report.xml").find("<testcase classname=\"baker validate\" name=\"bake settings\""),
            std::string::npos);

  // A sky twice as bright: |dE| = π in blue, against a reference mean of π(0.5 + 1 + 2)/3.
  test::writeReferenceDirectory(dir + "/ref", {{0, 0, 0}}, test::constantPanorama(64, 32, Eigen::Vector3f(0.5f, 1.0f, 2.0f)), 2);
  const test::ProcessResult brighter = test::runBaker(dir, "validate sky.vdb --against-reference ref --json");
  EXPECT_EQ(brighter.exitCode, 1) << brighter.out << brighter.err;
  EXPECT_NEAR(nlohmann::json::parse(brighter.out)["max_relative_error"].get<double>(), 6.0 / 7.0, 0.01);
}

}  // namespace
}  // namespace baker
