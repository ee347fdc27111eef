#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <openvdb/openvdb.h>
#include <string>
#include <vector>

#include "bake/ProbeConvergence.h"
#include "basis/BasisRegistry.h"
#include "basis/DiffuseResponse.h"
#include "basis/DirectionSet.h"
#include "basis/GramOperators.h"
#include "common/Error.h"
#include "formats/ReconstructionData.h"
#include "formats/VolumeReader.h"
#include "formats/VolumeReconstruction.h"
#include "formats/VolumeWriter.h"
#include "scene/RayTracer.h"
#include "tests/BakerProcess.h"
#include "tests/TestData.h"
#include "tests/TransportTestSupport.h"

namespace baker {
namespace {

// One Ambient Dice SRBF lobe of the seed post, 0.35·max(s·v, 0)² + 0.25·max(s·v, 0)⁴, about +Z.
class SeedSrbfLobe : public SphericalFunctions {
 public:
  int count() const override { return 1; }
  void evaluate(const Eigen::Vector3d& d, double* values) const override {
    const double c = std::max(0.0, d.z());
    values[0] = 0.35 * c * c + 0.25 * c * c * c * c;
  }
  std::vector<Eigen::Vector3d> kinkPlanes() const override { return {Eigen::Vector3d::UnitZ()}; }
};

// K_i(n) = ∫ f_i(ω) max(0, n·ω) dω by brute force over a dense spherical Fibonacci set.
std::vector<double> bruteForceResponse(const SphericalFunctions& f, const DirectionSet& dense, const Eigen::Vector3d& n) {
  std::vector<double> k(std::size_t(f.count()), 0.0), values(std::size_t(f.count()));
  for (std::size_t s = 0; s < dense.size(); ++s) {
    const double cosine = std::max(0.0, n.dot(dense.directions[s]));
    if (cosine == 0.0) continue;
    f.evaluate(dense.directions[s], values.data());
    for (int i = 0; i < f.count(); ++i) k[std::size_t(i)] += dense.weights[s] * cosine * values[std::size_t(i)];
  }
  return k;
}

// Every function's diffuse response against a dense quadrature of its definition, for lobes,
// SH and the piecewise Ambient Dice functions alike.
TEST(DiffuseResponse, MatchesADenseQuadratureOfTheDefinition) {
  const DirectionSet dense = sphericalFibonacci(400000);
  for (const char* name : {"ad-srbf", "sg-12", "sh-l2", "ad-linear", "ambient-cube"}) {
    const auto basis = makeBasis(name);
    const DiffuseResponse response(basis->functions(0), name);
    std::vector<double> k(std::size_t(response.count()));
    for (const Eigen::Vector3d& n : sphericalFibonacci(12).directions) {
      response.evaluate(n, k.data());
      const std::vector<double> expected = bruteForceResponse(basis->functions(0), dense, n);
      const double largest = *std::max_element(expected.begin(), expected.end());
      for (int i = 0; i < response.count(); ++i)
        EXPECT_NEAR(k[std::size_t(i)], expected[std::size_t(i)], 2e-5 * largest) << name << " function " << i;
    }
  }
}

// The seed post's polynomial fit of one SRBF lobe's diffuse response, per unit radiance and
// divided by π: I(θ) = 0.05981 + 0.12918 cos θ + 0.07056 cos² θ. The exact response at θ = 0 is
// 2(0.35/4 + 0.25/6) = 0.258333 and at θ = π is 0; the fit is within 0.0013 of it everywhere
// (0.5 % of the peak), which is the fit's own error, not the response's.
TEST(DiffuseResponse, OneSrbfLobeMatchesTheSeedsPolynomialFitWithinItsError) {
  const SeedSrbfLobe lobe;
  const DiffuseResponse response(lobe, "seed SRBF lobe");
  double k = 0.0, worst = 0.0;
  response.evaluate(Eigen::Vector3d::UnitZ(), &k);
  EXPECT_NEAR(k / M_PI, 2.0 * (0.35 / 4.0 + 0.25 / 6.0), 1e-6);
  response.evaluate(-Eigen::Vector3d::UnitZ(), &k);
  EXPECT_NEAR(k, 0.0, 1e-6);
  for (int step = 0; step <= 180; ++step) {
    const double theta = M_PI * step / 180.0;
    response.evaluate(Eigen::Vector3d(std::sin(theta), 0.0, std::cos(theta)), &k);
    const double c = std::cos(theta), fit = 0.05981 + 0.12918 * c + 0.07056 * c * c;
    worst = std::max(worst, std::abs(k / M_PI - fit));
  }
  EXPECT_LT(worst, 0.0013);
  EXPECT_GT(worst, 0.0005) << "the fit is not exact: an error this small means the response is not the lobe's";
}

// A constant sky L: each basis that holds a constant holds it exactly from a radiance bake
// (the least-squares fit reproduces what the functions span), so L(ω) = L, E(n) = π·L and sky
// visibility 1 for every direction, with the linear and the non-negative fit, from a fixed
// lattice and from a quality preset's rounds of lattices alike.
TEST(RadianceVolume, AConstantSkyIsHeldExactly) {
  Scene scene;
  const Eigen::Vector3f sky(0.5f, 1.0f, 2.0f);
  scene.environment = Environment::constant(sky);
  const RayTracer tracer(scene);
  const QualityPreset* preset = findQualityPreset("default");
  ASSERT_NE(preset, nullptr);
  auto expectHeld = [&](const std::string& name, bool nonNegative, bool rounds) {
    const auto basis = makeBasis(name);
    BakeSettings settings;
    settings.rays = rounds ? preset->rays : 256;
    if (rounds) settings.convergence = preset->convergence;
    settings.projection.signal = StoredSignal::Radiance;
    settings.projection.nonNegative = nonNegative;
    const test::BakedProbe probe = test::bakeProbe(scene, tracer, *basis, settings, Eigen::Vector3f::Zero());
    const VolumeReconstruction reading(makeBasis(name), StoredSignal::Radiance);
    const std::string what = name + (nonNegative ? " non-negative" : "") + (rounds ? " in rounds" : "");
    for (const Eigen::Vector3d& d : sphericalFibonacci(64).directions) {
      EXPECT_LT((reading.radiance(probe.coefficients.data(), d) - sky).cwiseAbs().maxCoeff(), 1e-4f * sky.maxCoeff())
          << what;
      EXPECT_LT((reading.irradiance(probe.coefficients.data(), d) - float(M_PI) * sky).cwiseAbs().maxCoeff(),
                1e-4f * float(M_PI) * sky.maxCoeff())
          << what;
      EXPECT_NEAR(reading.skyVisibility(probe.visibility.data(), d), 1.0, 1e-4) << what;
    }
  };
  for (const char* name : {"ad-srbf", "sh-l2", "sh-l4", "ambient-cube"})
    for (bool rounds : {false, true}) {
      expectHeld(name, false, rounds);
      if (admitsNonNegativeFit(*makeBasis(name))) expectHeld(name, true, rounds);
    }
}

// Lobes that cannot sum to a constant (spherical Gaussians) still give the sky's irradiance
// closely: the diffuse response smooths the fit's ripple.
TEST(RadianceVolume, SphericalGaussiansFitAConstantSkyCloselyInIrradiance) {
  Scene scene;
  scene.environment = Environment::constant(Eigen::Vector3f::Ones());
  const RayTracer tracer(scene);
  const auto basis = makeBasis("sg-12");
  BakeSettings settings;
  settings.rays = 256;
  settings.projection.signal = StoredSignal::Radiance;
  const test::BakedProbe probe = test::bakeProbe(scene, tracer, *basis, settings, Eigen::Vector3f::Zero());
  const VolumeReconstruction reading(makeBasis("sg-12"), StoredSignal::Radiance);
  double worstRadiance = 0.0, worstIrradiance = 0.0;
  for (const Eigen::Vector3d& d : sphericalFibonacci(256).directions) {
    worstRadiance = std::max(worstRadiance, double(std::abs(reading.radiance(probe.coefficients.data(), d).x() - 1.0f)));
    worstIrradiance = std::max(worstIrradiance,
                               double(std::abs(reading.irradiance(probe.coefficients.data(), d).x() / M_PI - 1.0)));
  }
  EXPECT_LT(worstIrradiance, 0.01);
  EXPECT_LT(worstIrradiance, worstRadiance);
}

// A directional light is a delta: its radiance coefficients are its exact projection
// G⁻¹·f(ω)·E in every channel, with no SH truncation between, also for a basis whose channels use
// different functions (ad-ycocg: Y in one set, Co and Cg in another, moments stacked).
TEST(RadianceVolume, APunctualLightIsProjectedExactly) {
  Scene scene;
  PunctualLight sun;
  sun.type = PunctualLight::Type::Directional;
  sun.intensity = 3.0f;
  sun.color = Eigen::Vector3f(1.0f, 0.6f, 0.2f);
  sun.direction = Eigen::Vector3f(0.3f, -1.0f, 0.2f).normalized();
  scene.lights.push_back(sun);
  const RayTracer tracer(scene);
  for (const char* name : {"ad-srbf", "sg-12", "sh-l2", "ad-ycocg"}) {
    const auto basis = makeBasis(name);
    BakeSettings settings;
    settings.rays = 64;
    settings.transport.bounces = 0;
    settings.projection.signal = StoredSignal::Radiance;
    const test::BakedProbe probe = test::bakeProbe(scene, tracer, *basis, settings, Eigen::Vector3f::Zero());
    const Eigen::Vector3f e = toColorSpace(basis->colorSpace(), sun.color * sun.intensity);
    for (int c = 0; c < 3; ++c) {
      const SphericalFunctions& f = basis->functions(c);
      Eigen::VectorXd values(f.count());
      f.evaluate(-sun.direction.cast<double>(), values.data());
      const Eigen::VectorXd expected = GramOperators(f, name).gramInverse() * values * double(e[c]);
      const float* got = probe.coefficients.data() + basis->coefficientOffset(c);
      for (int i = 0; i < f.count(); ++i)
        EXPECT_NEAR(got[i], expected[i], 1e-5 * expected.cwiseAbs().maxCoeff() + 1e-7)
            << name << " channel " << c << " coefficient " << i;
    }
  }
}

// The command line: the file says which signal it holds, `inspect` and `sample` report it, and a
// radiance bake's irradiance agrees with an irradiance bake of the same scene.
TEST(RadianceVolume, TheFileRecordsItsSignalAndSampleReconstructsIrradiance) {
  const std::string dir = test::makeTempDir("radiance_volume");
  const std::string scene = test::sourcePath("data/default_room/default_room.gltf");
  for (const char* signal : {"radiance", "irradiance"}) {
    const test::ProcessResult bake =
        test::runBaker(dir, {scene, "--basis", "sh-l4", "--signal", signal, "--rays", "1024", "--spacing", "1",
                             "--out", std::string(signal) + ".vdb", "--quiet"});
    ASSERT_EQ(bake.exitCode, 0) << bake.err;
  }
  const test::ProcessResult inspect = test::runBaker(dir, {"inspect", "radiance.vdb", "--json"});
  ASSERT_EQ(inspect.exitCode, 0) << inspect.err;
  EXPECT_EQ(nlohmann::json::parse(inspect.out)["signal"], "radiance");
  const Volume radiance = readVolume(dir + "/radiance.vdb");
  EXPECT_EQ(radiance.settings.at("signal"), "radiance");
  // A decoder that reads only "baker.reconstruction" learns the signal there too.
  openvdb::initialize();
  openvdb::io::File file(dir + "/radiance.vdb");
  file.open();
  const std::string reconstruction = file.getMetadata()->metaValue<std::string>("baker.reconstruction");
  file.close();
  EXPECT_EQ(nlohmann::json::parse(reconstruction)["signal"], "radiance");
  Eigen::Vector3d e[2];
  int k = 0;
  for (const char* file : {"radiance.vdb", "irradiance.vdb"}) {
    const test::ProcessResult sample = test::runBaker(dir, {"sample", file, "--at", "0,1,0", "--normal", "0,1,0", "--json"});
    ASSERT_EQ(sample.exitCode, 0) << sample.err;
    const nlohmann::json j = nlohmann::json::parse(sample.out);
    EXPECT_EQ(j["signal"], k == 0 ? "radiance" : "irradiance");
    const auto v = j["irradiance"].get<std::vector<double>>();
    e[k++] = Eigen::Vector3d(v[0], v[1], v[2]);
  }
  // sh-l4 radiance holds every band the clamped cosine passes up to 4; the irradiance fit stops at
  // the same bands, so both read the same E up to the samples' noise.
  EXPECT_LT((e[0] - e[1]).cwiseAbs().maxCoeff(), 0.03 * e[1].maxCoeff()) << e[0].transpose() << " vs " << e[1].transpose();

  // The viewer's decoder reconstructs irradiance volumes only: it refuses, naming the file.
  const test::ProcessResult view = test::runBaker(dir, {"view", "radiance.vdb", "--out", "page"});
  EXPECT_EQ(view.exitCode, 2);
  EXPECT_NE(view.err.find("radiance.vdb"), std::string::npos) << view.err;
  EXPECT_FALSE(std::filesystem::exists(dir + "/page"));
}

// What a volume holds is read from its settings: none recorded (volumes older than radiance) is
// irradiance; a value this version does not know is refused, not read as irradiance.
TEST(StoredSignal, MissingIsIrradianceAndUnknownIsRefused) {
  EXPECT_EQ(storedSignalOf({}), StoredSignal::Irradiance);
  EXPECT_EQ(storedSignalOf({{"signal", "radiance"}}), StoredSignal::Radiance);
  EXPECT_EQ(storedSignalOf({{"signal", "irradiance"}}), StoredSignal::Irradiance);
  EXPECT_THROW(storedSignalOf({{"signal", "specular"}}), InputError);
  EXPECT_THROW(parseStoredSignal("Radiance"), SettingError);
}

// Engine exports hold irradiance, whatever the bake stored: three.js's SH radiance is the radiance
// volume's own sh-l2 coefficients, Bevy's ambient cube its diffuse response at the six axes.
TEST(RadianceVolume, EngineExportsOfARadianceBakeHoldItsIrradiance) {
  const std::string dir = test::makeTempDir("radiance_exports");
  const std::string scene = test::sourcePath("data/default_room/default_room.gltf");
  for (const char* format : {"threejs", "bevy"}) {
    const test::ProcessResult bake =
        test::runBaker(dir, {scene, "--basis", "sh-l2", "--signal", "radiance", "--rays", "256", "--spacing", "1",
                             "--format", format, "--out", std::string("room_") + format, "--quiet"});
    ASSERT_EQ(bake.exitCode, 0) << bake.err;
  }
  const test::ProcessResult vdb = test::runBaker(dir, {scene, "--basis", "sh-l2", "--signal", "radiance", "--rays",
                                                       "256", "--spacing", "1", "--out", "room.vdb", "--quiet"});
  ASSERT_EQ(vdb.exitCode, 0) << vdb.err;
  const Volume source = readVolume(dir + "/room.vdb");
  const VolumeReconstruction sourceReading(source);
  for (const char* format : {"threejs", "bevy"}) {
    const Volume exported = readVolume(dir + "/room_" + format);
    const std::string conversion = volumeConversion({"x", std::string(format) == "bevy" ? VolumeFormat::Bevy
                                                                                        : VolumeFormat::ThreeJs},
                                                    *makeBasis("sh-l2"), StoredSignal::Radiance);
    EXPECT_NE(conversion.find("sh-l2 radiance"), std::string::npos) << conversion;
    EXPECT_EQ(exported.settings.at("signal"), "irradiance") << format;
    EXPECT_EQ(exported.settings.at("source_signal"), "radiance") << format;
    const VolumeReconstruction reading(exported);
    const Eigen::Vector3d axes[3] = {Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(), -Eigen::Vector3d::UnitZ()};
    for (std::int64_t p = 0; p < source.grid.probeCount(); p += 7)
      for (const Eigen::Vector3d& n : axes) {
        const Eigen::Vector3f expected = sourceReading.irradiance(source.probe(p), n);
        const Eigen::Vector3f got = reading.irradiance(exported.probe(p), n);
        // Bevy's RGB9E5 keeps 9 bits of mantissa; three.js's JSON its integer steps.
        EXPECT_LT((got - expected).cwiseAbs().maxCoeff(), 0.01f * expected.cwiseAbs().maxCoeff() + 1e-4f)
            << format << " probe " << p;
      }
  }
}

TEST(RadianceVolume, BadRequestsAreRefusedNamingTheFlag) {
  const std::string dir = test::makeTempDir("radiance_bad");
  const std::string scene = test::sourcePath("data/default_room/default_room.gltf");
  const test::ProcessResult unknown = test::runBaker(dir, {scene, "--signal", "specular", "--out", "x.vdb"});
  EXPECT_EQ(unknown.exitCode, 2);
  EXPECT_NE(unknown.err.find("--signal"), std::string::npos) << unknown.err;
  const test::ProcessResult window =
      test::runBaker(dir, {scene, "--signal", "radiance", "--window", "2", "--out", "x.vdb"});
  EXPECT_EQ(window.exitCode, 2);
  EXPECT_NE(window.err.find("--window"), std::string::npos) << window.err;
  // Lobes too sharp to integrate are refused before tracing, not when read (a lobe whose diffuse
  // response has no converged series is sharper still: LegendreResponse.ALobeTooSharpIsRefused).
  const test::ProcessResult sharp = test::runBaker(
      dir, {scene, "--basis", "sg-12", "--sg-sharpness", "300", "--signal", "radiance", "--out", "x.vdb"});
  EXPECT_EQ(sharp.exitCode, 2);
  EXPECT_NE(sharp.err.find("too sharp"), std::string::npos) << sharp.err;
  EXPECT_FALSE(std::filesystem::exists(dir + "/x.vdb"));
}

}  // namespace
}  // namespace baker
