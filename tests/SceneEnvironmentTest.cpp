#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "common/Error.h"
#include "scene/Environment.h"
#include "scene/GltfLoader.h"
#include "scene/RayTracer.h"
#include "scene/SceneOptions.h"
#include "scene/Shading.h"
#include "tests/GltfTestAssets.h"
#include "tests/TestData.h"

namespace baker {
namespace {

// The panorama convention of ../shared/tools/README.md, written out independently of the
// loader: the direction at the centre of pixel (i, j) of a W × H lat-long image.
Eigen::Vector3f pixelDirection(int i, int j, int width, int height) {
  const double u = (i + 0.5) / width, v = (j + 0.5) / height;
  const double phi = 2 * M_PI * (u - 0.5), theta = M_PI * v;
  return Eigen::Vector3d(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi)).cast<float>();
}

// An image whose texel (i, j) holds (i, j, 1): every lookup says which texel it read.
std::vector<float> indexImage(int width, int height) {
  std::vector<float> rgb;
  for (int j = 0; j < height; ++j)
    for (int i = 0; i < width; ++i) rgb.insert(rgb.end(), {float(i), float(j), 1.0f});
  return rgb;
}

TEST(SceneEnvironment, LookupFollowsThePanoramaConvention) {
  const int w = 64, h = 32;
  const Environment env = Environment::latLong(w, h, indexImage(w, h), 1.0f, 0.0f, "index");
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) ASSERT_EQ(env.radiance(pixelDirection(i, j, w, h)), Eigen::Vector3f(i, j, 1));
  // The README's landmarks: the image centre looks along +X, u = 0.75 along +Z, the top row up.
  EXPECT_EQ(env.texelOf(Eigen::Vector3f(1, 0, 0)).x(), w / 2);
  EXPECT_EQ(env.texelOf(Eigen::Vector3f(0, 0, 1)).x(), 3 * w / 4);
  EXPECT_EQ(env.texelOf(Eigen::Vector3f(0, 0, -1)).x(), w / 4);
  EXPECT_EQ(env.texelOf(Eigen::Vector3f(0, 1, 0)).y(), 0);
  EXPECT_EQ(env.texelOf(Eigen::Vector3f(0, -1, 0)).y(), h - 1);
}

TEST(SceneEnvironment, RotationTurnsTheMapAboutYRightHanded) {
  const int w = 64, h = 32;
  const Environment plain = Environment::latLong(w, h, indexImage(w, h), 1.0f, 0.0f, "index");
  const Environment turned = Environment::latLong(w, h, indexImage(w, h), 2.0f, 90.0f, "index");
  // +90° about +Y takes +Z to +X: what was seen along +Z is now seen along +X (twice as bright).
  EXPECT_EQ(turned.radiance(Eigen::Vector3f(1, 0, 0)), 2.0f * plain.radiance(Eigen::Vector3f(0, 0, 1)));
  EXPECT_EQ(turned.radiance(Eigen::Vector3f(0, 0, -1)), 2.0f * plain.radiance(Eigen::Vector3f(1, 0, 0)));
  EXPECT_EQ(turned.radiance(Eigen::Vector3f(0, 1, 0)), 2.0f * plain.radiance(Eigen::Vector3f(0, 1, 0)));
}

// Texel solid angle, from the README: (2π/W)(cos(πj/H) − cos(π(j+1)/H)).
double texelSolidAngle(int j, int width, int height) {
  return 2 * M_PI / width * (std::cos(M_PI * j / height) - std::cos(M_PI * (j + 1) / height));
}

TEST(SceneEnvironment, ImportanceSamplingMatchesItsDensity) {
  const int w = 16, h = 8;
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  std::vector<float> rgb(w * h * 3);
  for (float& x : rgb) x = uniform(rng) < 0.3f ? 0.0f : uniform(rng) * 10.0f;
  const Environment env = Environment::latLong(w, h, rgb, 1.5f, 30.0f, "random");
  // Map texel (i, j) is seen along its pixel direction turned by +30° about +Y.
  const float c = std::cos(float(M_PI / 6)), sn = std::sin(float(M_PI / 6));
  auto worldDirection = [&](int i, int j) {
    const Eigen::Vector3f d = pixelDirection(i, j, w, h);
    return Eigen::Vector3f(c * d.x() + sn * d.z(), d.y(), -sn * d.x() + c * d.z());
  };
  double luminanceIntegral = 0.0;
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i)
      luminanceIntegral += luminance(1.5f * Eigen::Vector3f::Map(&rgb[3 * (j * w + i)])) * texelSolidAngle(j, w, h);
  // The density is luminance / ∫ luminance, texel by texel, so it integrates to 1.
  std::vector<double> expected(w * h);
  double integral = 0.0;
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      const Eigen::Vector3f d = worldDirection(i, j);
      ASSERT_EQ(env.texelOf(d), Eigen::Vector2i(i, j));
      const double lum = luminance(1.5f * Eigen::Vector3f::Map(&rgb[3 * (j * w + i)]));
      EXPECT_NEAR(env.pdf(d), lum / luminanceIntegral, 1e-5 * (1 + lum / luminanceIntegral));
      expected[j * w + i] = lum * texelSolidAngle(j, w, h) / luminanceIntegral;
      integral += env.pdf(d) * texelSolidAngle(j, w, h);
    }
  EXPECT_NEAR(integral, 1.0, 1e-5);
  // Samples: the reported density and radiance are those of the direction drawn (but for the
  // odd sample on a texel edge, where float rounding may look up the neighbour), and texels are
  // drawn in proportion to their probability (a 5σ band on each count).
  const int n = 200000;
  std::vector<int> counts(w * h, 0);
  int inconsistent = 0;
  for (int k = 0; k < n; ++k) {
    const Environment::Sample s = env.sample(uniform(rng), uniform(rng));
    ASSERT_GT(s.pdf, 0.0f);
    ASSERT_NEAR(s.direction.norm(), 1.0f, 1e-5f);
    if (s.radiance != env.radiance(s.direction) || std::abs(s.pdf - env.pdf(s.direction)) > 1e-4f * s.pdf)
      ++inconsistent;
    const Eigen::Vector2i t = env.texelOf(s.direction);
    ++counts[t.y() * w + t.x()];
  }
  EXPECT_LE(inconsistent, n / 10000);
  for (int t = 0; t < w * h; ++t) {
    const double mean = expected[t] * n, sigma = std::sqrt(mean * (1 - expected[t]));
    EXPECT_NEAR(counts[t], mean, 5 * sigma + 1) << "texel " << t;
  }
}

TEST(SceneEnvironment, ConstantSkyAndNone) {
  const Environment sky = Environment::constant(Eigen::Vector3f(0.1f, 0.2f, 0.3f));
  EXPECT_EQ(sky.radiance(Eigen::Vector3f(0, -1, 0)), Eigen::Vector3f(0.1f, 0.2f, 0.3f));
  EXPECT_FLOAT_EQ(sky.pdf(Eigen::Vector3f(1, 0, 0)), float(1 / (4 * M_PI)));
  const Environment::Sample s = sky.sample(0.3f, 0.6f);
  EXPECT_NEAR(s.direction.norm(), 1.0f, 1e-6f);
  EXPECT_TRUE(sky.emits());
  const Environment none;
  EXPECT_EQ(none.radiance(Eigen::Vector3f(1, 0, 0)), Eigen::Vector3f::Zero());
  EXPECT_EQ(none.sample(0.5f, 0.5f).pdf, 0.0f);
  EXPECT_FALSE(none.emits());
  EXPECT_FALSE(Environment::constant(Eigen::Vector3f::Zero()).emits());
}

TEST(SceneEnvironment, OptionsReadAMapSanitiseItAndRefuseBadValues) {
  const std::string dir = test::makeTempDir("environment-options");
  std::vector<float> rgb = indexImage(8, 4);
  rgb[0] = std::numeric_limits<float>::quiet_NaN();
  rgb[5] = -1.0f;
  rgb[7] = std::numeric_limits<float>::infinity();
  test::writeFloatImage(dir + "/env.exr", 8, 4, rgb);
  SceneOptions options;
  options.environmentMap = dir + "/env.exr";
  options.environmentIntensity = 2.0;
  std::vector<std::string> warnings;
  const Environment env = environmentFromOptions(options, warnings);
  EXPECT_EQ(env.kind(), Environment::Kind::Map);
  EXPECT_EQ(env.sanitizedTexels(), 3u);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("env.exr: 3 texel(s) were negative or not finite and read as 0"), std::string::npos)
      << warnings[0];
  EXPECT_EQ(env.radiance(pixelDirection(0, 0, 8, 4)), Eigen::Vector3f::Zero());
  EXPECT_EQ(env.radiance(pixelDirection(3, 2, 8, 4)), Eigen::Vector3f(6, 4, 2));

  auto rejects = [&](const SceneOptions& bad, const std::string& needle) {
    std::vector<std::string> ignored;
    try {
      environmentFromOptions(bad, ignored);
      ADD_FAILURE() << needle;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
    }
  };
  SceneOptions both = options;
  both.sky = "1,1,1";
  rejects(both, "sky and an environment map both describe the environment");
  SceneOptions nanIntensity = options;
  nanIntensity.environmentIntensity = std::nan("");
  rejects(nanIntensity, "env_intensity must be a finite non-negative number");
  for (const char* sky : {"1,2", "1,2,3,4", "1,-2,3", "1,x,3", "1,2,", "nan,1,1"}) {
    SceneOptions bad;
    bad.sky = sky;
    rejects(bad, "sky must be three finite non-negative numbers");
  }
  SceneOptions good;
  good.sky = "0.5,1,2";
  EXPECT_EQ(environmentFromOptions(good, warnings).constantRadiance(), Eigen::Vector3f(0.5f, 1, 2));
}

// axes_markers puts an emissive cube 5 m out on each axis. An HDR painted, by the README's
// formula, with the colour of the marker each pixel's direction points nearest to must show the
// same colour as the marker a ray along that direction hits: the scene frame, the environment
// map and the panorama convention agree.
TEST(SceneEnvironment, AxesMarkersLineUpWithAGeneratedPanorama) {
  REQUIRE_SHARED_DATA();
  const std::string dir = test::makeTempDir("axes-panorama");
  const int w = 128, h = 64;
  const Eigen::Vector3f colors[6] = {{1, 0, 0}, {0, 1, 1}, {0, 1, 0}, {1, 0, 1}, {0, 0, 1}, {1, 1, 0}};  // ±X, ±Y, ±Z
  auto markerOf = [](const Eigen::Vector3f& d) {
    int axis = 0;
    d.cwiseAbs().maxCoeff(&axis);
    return 2 * axis + (d[axis] < 0 ? 1 : 0);
  };
  std::vector<float> rgb;
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < w; ++i) {
      const Eigen::Vector3f c = colors[markerOf(pixelDirection(i, j, w, h))];
      rgb.insert(rgb.end(), {c.x(), c.y(), c.z()});
    }
  test::writeFloatImage(dir + "/markers.hdr", w, h, rgb);
  SceneOptions options;
  options.environmentMap = dir + "/markers.hdr";
  const Scene scene = loadGltf(test::sharedDataPath("scenes/axes_markers/axes_markers.gltf"), options);
  const RayTracer tracer(scene);
  // The six axes and directions 3° off them (the markers subtend about 4.6°).
  std::vector<Eigen::Vector3f> directions;
  for (int m = 0; m < 6; ++m) {
    Eigen::Vector3f axis = Eigen::Vector3f::Zero();
    axis[m / 2] = m % 2 ? -1.0f : 1.0f;
    const Eigen::Vector3f side = axis.unitOrthogonal();
    directions.push_back(axis);
    directions.push_back((axis + std::tan(float(3 * M_PI / 180)) * side).normalized());
  }
  for (const Eigen::Vector3f& d : directions) {
    Hit hit;
    tracer.intersect8(Eigen::Vector3f::Zero(), &d, 1, &hit);
    ASSERT_FALSE(hit.missed()) << d.transpose();
    const SurfaceSample marker = shadeSurface(scene, scene.instances[hit.instance].mesh, hit.triangle, hit.u, hit.v);
    EXPECT_EQ(marker.emission, colors[markerOf(d)]) << d.transpose();
    EXPECT_EQ(scene.environment.radiance(d), marker.emission) << d.transpose();
  }
}

}  // namespace
}  // namespace baker
