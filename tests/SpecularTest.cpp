#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <openvdb/openvdb.h>
#include <string>
#include <vector>

#include "bake/ProbeBaker.h"
#include "basis/BasisRegistry.h"
#include "basis/DirectionSet.h"
#include "basis/GgxLobe.h"
#include "basis/SpecularBlend.h"
#include "formats/VolumeReconstruction.h"
#include "scene/RayTracer.h"
#include "tests/BakerProcess.h"
#include "tests/TestData.h"
#include "tests/TransportTestSupport.h"

// Glossy specular from radiance volumes: the GGX lobe against closed forms and a direct
// integration of its density, the blend against exact lobe integrals, and `sample`'s flags.
namespace baker {
namespace {

Eigen::Vector3d viewAt(double cosView) { return {std::sqrt(1.0 - cosView * cosView), 0.0, cosView}; }

// At α = 1 the GGX density is 1/π in the half vector, and facing the view G2 = 2μ/(1 + μ), so
// A = ∫ μ/(2π(1 + μ)) dω over the hemisphere = 1 − ln 2.
TEST(GgxLobe, AlbedoAtRoughnessOneFacingTheViewIsOneMinusLn2) {
  const GgxLobe lobe(Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitZ(), 1.0);
  EXPECT_NEAR(lobe.albedo(), 1.0 - std::log(2.0), 2e-4);
}

// The importance-sampled quadrature against a dense spherical Fibonacci sum of the closed-form
// ρ(ω)(n·ω)⁺, for a smooth radiance and for 1 (the albedo).
TEST(GgxLobe, QuadratureMatchesTheDensityIntegratedDirectly) {
  const DirectionSet dense = sphericalFibonacci(200000);
  const auto radiance = [](const Eigen::Vector3d& w) { return 1.0 + 0.5 * w.x() + w.z() * w.z(); };
  for (double roughness : {0.3, 0.6, 1.0})
    for (double cosView : {1.0, 0.5, 0.1}) {
      const GgxLobe lobe(Eigen::Vector3d::UnitZ(), viewAt(cosView), roughness);
      double direct = 0.0, directAlbedo = 0.0;
      for (std::size_t i = 0; i < dense.size(); ++i) {
        const double w = dense.weights[i] * lobe.cosineWeighted(dense.directions[i]);
        direct += w * radiance(dense.directions[i]);
        directAlbedo += w;
      }
      const DirectionSet q = lobe.quadrature(64, 128);
      double sampled = 0.0;
      for (std::size_t i = 0; i < q.size(); ++i) sampled += q.weights[i] * radiance(q.directions[i]);
      EXPECT_NEAR(lobe.albedo(), directAlbedo, 2e-3 * directAlbedo) << roughness << " " << cosView;
      EXPECT_NEAR(sampled, direct, 2e-3 * direct) << roughness << " " << cosView;
    }
}

TEST(GgxLobe, RoughnessZeroIsTheMirror) {
  const Eigen::Vector3d n = Eigen::Vector3d(0.2, 1.0, -0.3).normalized(), v = Eigen::Vector3d(1.0, 0.4, 0.0).normalized();
  const GgxLobe lobe(n, v, 0.0);
  const DirectionSet q = lobe.quadrature(8, 8);
  double total = 0.0;
  for (std::size_t i = 0; i < q.size(); ++i) {
    EXPECT_LT((q.directions[i] - (2.0 * n.dot(v) * n - v)).norm(), 1e-12);
    total += q.weights[i];
  }
  EXPECT_NEAR(total, 1.0, 1e-12);
}

TEST(SpecularBlend, MirrorAtRoughnessZeroAndABlendEverywhere) {
  for (const char* name : {"ad-srbf", "sh-l2", "sg-12"}) {
    const std::shared_ptr<const SpecularBlend> blend = specularBlendOf(*makeBasis(name));
    for (int k = 0; k <= 20; ++k) {
      const double cosView = k / 20.0;
      EXPECT_EQ(blend->diffuseWeight(0.0, cosView), 0.0) << name;
      EXPECT_NEAR(blend->albedo(0.0, cosView), 1.0, 1e-9) << name;
      for (int j = 0; j <= 20; ++j) {
        const double w = blend->diffuseWeight(j / 20.0, cosView);
        EXPECT_TRUE(w >= 0.0 && w <= 1.0) << name << " " << w;
      }
    }
    EXPECT_NEAR(blend->albedo(1.0, 1.0), 1.0 - std::log(2.0), 2e-4) << name;
    // The rough end reads mostly the diffuse term, and facing the view entirely.
    EXPECT_GT(blend->diffuseWeight(1.0, 1.0), 0.95) << name;
  }
}

// The blend against the exact GGX integral of radiance that is one of the basis's own lobes, in
// every direction relative to the frame: exact at roughness 0, and close where the lobe is wide
// against the basis's functions (the table is least-squares best, not exact, in between).
TEST(SpecularBlend, FollowsTheExactIntegralOfALobe) {
  const auto basis = makeBasis("ad-srbf");
  const VolumeReconstruction reading(makeBasis("ad-srbf"), StoredSignal::Radiance);
  const Eigen::Vector3d n = Eigen::Vector3d(0.3, 0.9, 0.1).normalized();
  const Eigen::Vector3d v = (n + Eigen::Vector3d(0.8, -0.1, 0.4)).normalized();
  for (double roughness : {0.0, 1.0}) {
    const GgxLobe lobe(n, v, roughness);
    const DirectionSet q = lobe.quadrature(64, 128);
    double worst = 0.0;
    for (int i = 0; i < basis->coefficientCount(0); ++i) {
      std::vector<float> c(std::size_t(basis->totalCoefficients()), 0.0f);
      for (int channel = 0; channel < 3; ++channel) c[std::size_t(basis->coefficientOffset(channel) + i)] = 1.0f;
      std::vector<double> values(std::size_t(basis->coefficientCount(0)));
      double exact = 0.0, albedo = 0.0;
      for (std::size_t s = 0; s < q.size(); ++s) {
        basis->functions(0).evaluate(q.directions[s], values.data());
        exact += q.weights[s] * values[std::size_t(i)];
        albedo += q.weights[s];
      }
      exact /= albedo;
      worst = std::max(worst, std::abs(double(reading.specular(c.data(), n, v, roughness).value.x()) - exact));
    }
    // One lobe peaks at 1/2 (the twelve sum to 1): at roughness 1 the blend is within 4 % of that
    // peak (measured 3.3 %).
    EXPECT_LT(worst, roughness == 0.0 ? 1e-6 : 0.02) << "roughness " << roughness;
  }
}

// For SH the fitted weight has a closed form: by the addition theorem, summed over a band's
// functions every product Y_lm(a) Y_lm(b) is (2l + 1)/(4π) P_l(a·b), so each frame gives the same
// sums, built from P_l(n·r) and the lobe's means of P_l(ω·n) and P_l(ω·r). Those means are taken
// here by a dense spherical Fibonacci sum of the closed-form density, not the lobe's quadrature.
TEST(SpecularBlend, ShWeightsMatchTheirClosedForm) {
  const std::shared_ptr<const SpecularBlend> blend = specularBlendOf(*makeBasis("sh-l2"));
  const DirectionSet dense = sphericalFibonacci(100000);
  const auto legendre = [](int l, double x) { return l == 1 ? x : 1.5 * x * x - 0.5; };
  const double k[3] = {1.0, 2.0 / 3.0, 0.25};  // A_l / π of the clamped cosine
  for (const auto& [j, kv] : std::vector<std::pair<int, int>>{{5, 15}, {5, 8}, {8, 4}, {10, 12}, {12, 6}, {15, 10}}) {
    const double roughness = j / 15.0, cosView = kv / 15.0;
    const Eigen::Vector3d n = Eigen::Vector3d::UnitZ();
    const GgxLobe lobe(n, viewAt(cosView), roughness);
    const Eigen::Vector3d r = lobe.reflection();
    double albedo = 0.0, aroundN[3] = {0, 0, 0}, aroundR[3] = {0, 0, 0};
    for (std::size_t i = 0; i < dense.size(); ++i) {
      const double w = dense.weights[i] * lobe.cosineWeighted(dense.directions[i]);
      albedo += w;
      for (int l = 1; l <= 2; ++l) {
        aroundN[l] += w * legendre(l, dense.directions[i].dot(n));
        aroundR[l] += w * legendre(l, dense.directions[i].dot(r));
      }
    }
    double aa = 0.0, ab = 0.0;
    for (int l = 1; l <= 2; ++l) {
      const double c = (2 * l + 1) / (4 * M_PI), p = legendre(l, n.dot(r));
      aa += c * (k[l] * k[l] - 2.0 * k[l] * p + 1.0);
      ab += c * (k[l] * aroundN[l] / albedo - k[l] * p - aroundR[l] / albedo + 1.0);
    }
    EXPECT_NEAR(blend->diffuseWeight(roughness, cosView), std::clamp(ab / aa, 0.0, 1.0), 0.01) << j << ", " << kv;
  }
}

// A constant sky is held exactly by bases that span constants, so S = L for every roughness and
// view, grazing and from below included; the samples' own reference gives L too, where the rays
// resolve the lobe.
TEST(Specular, AConstantSkyGivesItsRadianceAtEveryRoughness) {
  Scene scene;
  const Eigen::Vector3f sky(0.5f, 1.0f, 2.0f);
  scene.environment = Environment::constant(sky);
  const RayTracer tracer(scene);
  for (const char* name : {"ad-srbf", "sh-l2"}) {
    const auto basis = makeBasis(name);
    BakeSettings settings;
    settings.rays = 4096;
    settings.projection.signal = StoredSignal::Radiance;
    const test::BakedProbe probe = test::bakeProbe(scene, tracer, *basis, settings, Eigen::Vector3f::Zero());
    const VolumeReconstruction reading(makeBasis(name), StoredSignal::Radiance);
    const Eigen::Vector3d n = Eigen::Vector3d(0.1, 1.0, 0.2).normalized();
    for (const Eigen::Vector3d& view : sphericalFibonacci(16).directions)
      for (double roughness : {0.0, 0.1, 0.3, 0.6, 1.0}) {
        const Eigen::Vector3f s = reading.specular(probe.coefficients.data(), n, view, roughness).value;
        EXPECT_LT((s - sky).cwiseAbs().maxCoeff(), 1e-4f * sky.maxCoeff()) << name << " roughness " << roughness;
        if (roughness < 0.3 || n.dot(view) < 0.2) continue;
        const SampledSpecular reference = sampledSpecular(probe.samples, GgxLobe(n, view, roughness));
        EXPECT_NEAR(reference.rayCoverage, 1.0, 0.05) << roughness;
        EXPECT_LT((reference.value - sky).cwiseAbs().maxCoeff(), 1e-5f * sky.maxCoeff()) << roughness;
      }
  }
}

// A tiny bright source: a directional light, fitted ≥ 0 in non-negative lobes, gives finite
// specular ≥ 0 at every roughness and view, the mirror and grazing views included.
TEST(Specular, ADeltaLightStaysFiniteAndNonNegativeWithANonNegativeFit) {
  Scene scene;
  PunctualLight sun;
  sun.type = PunctualLight::Type::Directional;
  sun.intensity = 50.0f;
  sun.direction = Eigen::Vector3f(0.3f, -1.0f, 0.2f).normalized();
  scene.lights.push_back(sun);
  const RayTracer tracer(scene);
  for (const char* name : {"ad-srbf", "sg-12"}) {
    const auto basis = makeBasis(name);
    BakeSettings settings;
    settings.rays = 256;
    settings.transport.bounces = 0;
    settings.projection.signal = StoredSignal::Radiance;
    settings.projection.nonNegative = true;
    const test::BakedProbe probe = test::bakeProbe(scene, tracer, *basis, settings, Eigen::Vector3f::Zero());
    const VolumeReconstruction reading(makeBasis(name), StoredSignal::Radiance);
    const DirectionSet directions = sphericalFibonacci(32);
    for (const Eigen::Vector3d& n : directions.directions)
      for (const Eigen::Vector3d& view : directions.directions)
        for (double roughness : {0.0, 0.5, 1.0}) {
          const Eigen::Vector3f s = reading.specular(probe.coefficients.data(), n, view, roughness).value;
          EXPECT_TRUE(s.allFinite() && s.minCoeff() >= 0.0f) << name << " " << s.transpose();
        }
  }
}

// `sample --roughness R --view V`: the specular of a radiance volume, the blend's table in the
// file, and each bad request refused with exit 2 before any output.
TEST(Specular, SampleReadsItAndRefusesBadRequests) {
  const std::string dir = test::makeTempDir("specular_sample");
  const std::string scene = test::sourcePath("data/default_room/default_room.gltf");
  for (const char* signal : {"radiance", "irradiance"}) {
    const test::ProcessResult bake = test::runBaker(dir, {scene, "--basis", "ad-srbf", "--signal", signal, "--rays",
                                                          "256", "--spacing", "1", "--out", std::string(signal) + ".vdb",
                                                          "--quiet"});
    ASSERT_EQ(bake.exitCode, 0) << bake.err;
  }
  const std::vector<std::string> at = {"--at", "0,1,0", "--normal", "0,1,0"};
  const auto sample = [&](const std::string& file, std::vector<std::string> extra) {
    std::vector<std::string> args = {"sample", file};
    args.insert(args.end(), at.begin(), at.end());
    args.insert(args.end(), extra.begin(), extra.end());
    return test::runBaker(dir, args);
  };
  const test::ProcessResult rough = sample("radiance.vdb", {"--roughness", "1", "--view", "0,1,0", "--json"});
  ASSERT_EQ(rough.exitCode, 0) << rough.err;
  const nlohmann::json j = nlohmann::json::parse(rough.out);
  const auto e = j["irradiance"].get<std::vector<double>>();
  const auto s = j["specular"]["value"].get<std::vector<double>>();
  const double w = j["specular"]["diffuse_weight"].get<double>();
  // Roughness 1 facing the view reads (almost) only the diffuse term: the table says how much.
  EXPECT_GT(w, 0.95);
  if (w == 1.0)
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(s[std::size_t(c)], e[std::size_t(c)] / M_PI, 1e-6 * e[std::size_t(c)]);
  EXPECT_NEAR(j["specular"]["albedo"].get<double>(), 1.0 - std::log(2.0), 2e-4);
  EXPECT_TRUE(nlohmann::json::parse(sample("radiance.vdb", {"--json"}).out)["specular"].is_null());

  // The file carries the table decoders read, the one the library reads with.
  openvdb::initialize();
  openvdb::io::File file(dir + "/radiance.vdb");
  file.open();
  const nlohmann::json table = nlohmann::json::parse(file.getMetadata()->metaValue<std::string>("baker.specular"));
  file.close();
  EXPECT_EQ(table, specularBlendOf(*makeBasis("ad-srbf"))->describe());

  for (const auto& [args, message] : std::vector<std::pair<std::vector<std::string>, std::string>>{
           {{"--roughness", "1.5", "--view", "0,1,0"}, "--roughness must be in [0, 1]"},
           {{"--roughness", "-0.1", "--view", "0,1,0"}, "--roughness must be in [0, 1]"},
           {{"--roughness", "0.5", "--view", "0,0,0"}, "--view must not be zero"},
           {{"--roughness", "0.5"}, "--roughness and --view go together"}}) {
    const test::ProcessResult r = sample("radiance.vdb", args);
    EXPECT_EQ(r.exitCode, 2) << message;
    EXPECT_NE(r.err.find(message), std::string::npos) << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
  }
  const test::ProcessResult irradiance = sample("irradiance.vdb", {"--roughness", "0.5", "--view", "0,1,0"});
  EXPECT_EQ(irradiance.exitCode, 2);
  EXPECT_NE(irradiance.err.find("irradiance.vdb: holds irradiance"), std::string::npos) << irradiance.err;
}

// `probe --roughness R --view V --normal N`: the basis's specular beside the reference from the
// probe's own rays, which resolve a rough lobe (coverage near 1) and hold no mirror (null).
TEST(Specular, ProbeGivesTheReferenceFromItsOwnRays) {
  const std::string dir = test::makeTempDir("specular_probe");
  const std::string scene = test::sourcePath("data/default_room/default_room.gltf");
  const auto probe = [&](std::vector<std::string> extra) {
    std::vector<std::string> args = {"probe", scene, "--basis", "sh-l2", "--rays", "4096", "--at", "0,1,0"};
    args.insert(args.end(), extra.begin(), extra.end());
    return test::runBaker(dir, args);
  };
  for (const char* roughness : {"0.6", "0"}) {
    const test::ProcessResult r = probe({"--signal", "radiance", "--roughness", roughness, "--view", "0.6,0.8,0",
                                         "--normal", "0,1,0", "--json"});
    ASSERT_EQ(r.exitCode, 0) << r.err;
    const nlohmann::json s = nlohmann::json::parse(r.out)["probes"][0]["specular"];
    for (const char* key : {"normal", "view", "roughness", "value", "from_samples", "ray_coverage", "albedo"})
      EXPECT_TRUE(s.contains(key)) << key;
    if (std::string(roughness) == "0") {
      EXPECT_TRUE(s["from_samples"].is_null());
      EXPECT_EQ(s["ray_coverage"].get<double>(), 0.0);
      continue;
    }
    EXPECT_NEAR(s["ray_coverage"].get<double>(), 1.0, 0.05);
    for (double v : s["from_samples"].get<std::vector<double>>()) EXPECT_TRUE(std::isfinite(v) && v > 0.0);
  }
  for (const auto& [args, message] : std::vector<std::pair<std::vector<std::string>, std::string>>{
           {{"--roughness", "0.5", "--view", "0,1,0"}, "add --signal radiance"},
           {{"--signal", "radiance", "--normal", "0,1,0"}, "--normal goes with --roughness and --view"},
           {{"--signal", "radiance", "--roughness", "2", "--view", "0,1,0"}, "--roughness must be in [0, 1]"}}) {
    const test::ProcessResult r = probe(args);
    EXPECT_EQ(r.exitCode, 2) << message;
    EXPECT_NE(r.err.find(message), std::string::npos) << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out;
  }
}

}  // namespace
}  // namespace baker
