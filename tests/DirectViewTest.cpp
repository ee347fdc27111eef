#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "bake/LightAim.h"
#include "bake/PathRandom.h"
#include "bake/ProbeBaker.h"
#include "basis/DirectionSet.h"
#include "basis/ShBasis.h"
#include "scene/GltfLoader.h"
#include "scene/RayTracer.h"
#include "tests/SeedStatistics.h"
#include "tests/TestData.h"

// What a probe sees directly, sampled by importance and combined with the lattice by MIS
// (DirectView, LightAim): the estimate stays unbiased at small ray counts, where the samples
// carry most of the small bright sources, measured against closed forms over independent seeds.
namespace baker {
namespace {

using test::overSeeds;

std::vector<ProbeSamples> bakeSamples(const Scene& scene, const RayTracer& tracer, const BakeSettings& settings,
                                      const Eigen::Vector3f& position) {
  const ShBasis basis(2);
  const ProbeBaker baker(scene, tracer, basis, settings, 1);
  std::vector<float> coefficients(baker.coefficientsPerProbe()), visibility(baker.visibilityPerProbe());
  std::vector<ProbeSamples> samples;
  RayCounts counts;
  baker.bake({{position, 7, 0}}, coefficients.data(), visibility.data(), &counts, &samples);
  return samples;
}

// An aim's density is normalised and is the one its directions follow: the mean of 1/pdf over
// directions it draws is the sphere's area, 4π, for narrow and wide aims alike.
TEST(LightAim, DirectionsFollowTheDensity) {
  for (const float width : {5e-7f, 1e-3f, 0.05f, 0.5f}) {
    LightAim::Aim aim;
    aim.axis = Eigen::Vector3f(0.3f, -0.5f, 0.8f).normalized();
    aim.width = width;
    aim.logSpan = std::log1p(2.0f / width);
    PathRandom random(3, 5, 7);
    double inverse = 0.0;
    const int n = 400000;
    for (int i = 0; i < n; ++i) {
      const float xi1 = random.uniform(), xi2 = random.uniform();
      const Eigen::Vector3f d = LightAim::direction(aim, xi1, xi2);
      ASSERT_NEAR(d.norm(), 1.0f, 1e-5f);
      inverse += 1.0 / double(LightAim::density(aim, d));
    }
    EXPECT_NEAR(inverse / n, 4.0 * M_PI, 0.01 * 4.0 * M_PI) << "u0 = " << width;
    // Towards the axis the density is c/u₀, c = 1/(2π ln(1 + 2/u₀)).
    EXPECT_NEAR(LightAim::density(aim, aim.axis), 1.0 / (2.0 * M_PI * std::log1p(2.0 / width) * width),
                1e-4 / (2.0 * M_PI * std::log1p(2.0 / width) * width));
  }
}

// point_ground and spot_ground (a 10 cd light 2 m over a ρ = 0.5 ground): E(−Y) at (0,1,0) from
// the lit ground is 0.79885 and 0.55874. At 256 rays most of it comes from the directions aimed
// at the light; sixteen seeds must average to the closed form.
TEST(DirectView, AimsAtALightStayUnbiasedAtFewRays) {
  REQUIRE_SHARED_DATA();
  for (const auto& [name, expected] : {std::pair<std::string, double>{"point_ground", 0.79885}, {"spot_ground", 0.55874}}) {
    const Scene scene = loadGltf(test::sharedDataPath("scenes/" + name + "/" + name + ".gltf"));
    const RayTracer tracer(scene);
    std::vector<double> values;
    RayCounts counts;
    for (std::uint64_t seed = 1; seed <= 16; ++seed) {
      BakeSettings settings;
      settings.rays = 256;
      settings.transport.bounces = 1;
      settings.transport.directPunctual = false;
      settings.transport.seed = seed;
      const ProbeSamples s = bakeSamples(scene, tracer, settings, {0, 1, 0})[0];
      EXPECT_FALSE(s.direct.empty()) << name << ": the aimed samples found the lit ground";
      values.push_back(sampledIrradiance(s, {0, -1, 0}).x());
    }
    const test::SeedStatistics s = overSeeds(values);
    EXPECT_NEAR(s.mean, expected, 0.002 * expected + 3.0 * s.standardError) << name;
    EXPECT_LT(s.standardError, 0.01 * expected) << name;
  }
}

// An empty scene under a map of one very bright texel (a small sun, 10⁴ times the rest): the
// lattice of 64 directions finds the sun by chance, the sky samples always. E(n) is the exact
// integral of the piecewise-constant map against max(0, n·ω), summed over sub-texels.
TEST(DirectView, SkySamplesMakeASmallSunUnbiasedAtFewRays) {
  const int w = 32, h = 16;
  std::vector<float> rgb(std::size_t(w) * h * 3, 0.1f);
  const int sunColumn = 20, sunRow = 5;
  for (int c = 0; c < 3; ++c) rgb[(std::size_t(sunRow) * w + sunColumn) * 3 + c] = 1000.0f * (c + 1);
  Scene scene;
  scene.environment = Environment::latLong(w, h, rgb, 1.0f, 0.0f, "sun");
  const RayTracer tracer(scene);
  const Eigen::Vector3f normal = Eigen::Vector3f(0.4f, 0.8f, -0.3f).normalized();

  double exact[3] = {0, 0, 0};
  const int sub = 64;
  for (int row = 0; row < h; ++row)
    for (int column = 0; column < w; ++column)
      for (int j = 0; j < sub; ++j)
        for (int i = 0; i < sub; ++i) {
          const double u = (column + (i + 0.5) / sub) / w, v0 = double(row + double(j) / sub) / h,
                       v1 = double(row + double(j + 1) / sub) / h, v = 0.5 * (v0 + v1);
          const double phi = 2.0 * M_PI * (u - 0.5), theta = M_PI * v;
          const Eigen::Vector3d d(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
          const double solidAngle = 2.0 * M_PI / (w * sub) * (std::cos(M_PI * v0) - std::cos(M_PI * v1));
          const double cosine = std::max(0.0, normal.cast<double>().dot(d));
          for (int c = 0; c < 3; ++c)
            exact[c] += rgb[(std::size_t(row) * w + column) * 3 + c] * cosine * solidAngle;
        }
  std::vector<double> values[3];
  for (std::uint64_t seed = 1; seed <= 16; ++seed) {
    BakeSettings settings;
    settings.rays = 64;
    settings.transport.bounces = 0;
    settings.transport.seed = seed;
    const Eigen::Vector3f e = sampledIrradiance(bakeSamples(scene, tracer, settings, {0, 0, 0})[0], normal);
    for (int c = 0; c < 3; ++c) values[c].push_back(e[c]);
  }
  for (int c = 0; c < 3; ++c) {
    const test::SeedStatistics s = overSeeds(values[c]);
    EXPECT_NEAR(s.mean, exact[c], 0.002 * exact[c] + 3.0 * s.standardError) << "channel " << c;
    EXPECT_LT(s.standardError, 0.01 * exact[c]) << "channel " << c;
  }
}

// Each seed turns the lattice its own way (the rotations are drawn from the seed), and a
// seed turns it the same way in every bake.
TEST(DirectView, EachSeedTracesItsOwnLattice) {
  Scene scene;
  const RayTracer tracer(scene);
  const ShBasis basis(2);
  BakeSettings a, b;
  a.rays = b.rays = 64;
  a.transport.seed = 1;
  b.transport.seed = 2;
  const ProbeBaker first(scene, tracer, basis, a, 8), again(scene, tracer, basis, a, 8), other(scene, tracer, basis, b, 8);
  for (int r = 0; r < 8; ++r) {
    EXPECT_EQ(first.directions(r), again.directions(r)) << "rotation " << r;
    EXPECT_GT((first.directions(r)[0] - other.directions(r)[0]).norm(), 1e-3f) << "rotation " << r;
  }
}

}  // namespace
}  // namespace baker
