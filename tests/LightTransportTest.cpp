#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "bake/PathIntegrator.h"
#include "basis/DirectionSet.h"
#include "basis/ShBasis.h"
#include "scene/GltfLoader.h"
#include "scene/RayTracer.h"
#include "scene/Shading.h"
#include "tests/GltfTestAssets.h"
#include "tests/TestData.h"
#include "tests/TransportTestSupport.h"

// Exact checks of light transport on the scenes of ../shared/data/scenes, whose analytic
// values the data README states.
namespace baker {
namespace {

const Eigen::Vector3f kDown(0, -1, 0);

Scene sharedScene(const std::string& name) {
  return loadGltf(test::sharedDataPath("scenes/" + name + "/" + name + ".gltf"));
}

BakeSettings settingsWith(int rays, int bounces) {
  BakeSettings s;
  s.rays = rays;
  s.transport.bounces = bounces;
  return s;
}

// point_ground and spot_ground: a 10 cd light 2 m above a ρ = 0.5 ground. At (0,1,0) the
// ground's light gives E(−Y) = 0.79885 (point) and 0.55874 (spot, inner 20°, outer 40°); the
// light itself, straight up, adds nothing to −Y and E⊥ = 10/1² to +Y.
TEST(LightTransport, LightOverGroundIrradianceBelowTheProbe) {
  REQUIRE_SHARED_DATA();
  for (const auto& [name, expected] : {std::pair<std::string, double>{"point_ground", 0.79885}, {"spot_ground", 0.55874}}) {
    const Scene scene = sharedScene(name);
    const RayTracer tracer(scene);
    const ShBasis basis(2);
    const test::BakedProbe probe = test::bakeProbe(scene, tracer, basis, settingsWith(16384, 3), {0, 1, 0});
    EXPECT_NEAR(sampledIrradiance(probe.samples, kDown).x(), expected, 0.005 * expected) << name;
    ASSERT_EQ(probe.samples.punctual.size(), 1u) << name;
    EXPECT_NEAR(sampledIrradiance(probe.samples, -kDown).x(), 10.0f, 1e-4f) << name;
    EXPECT_EQ(probe.rays.emitterShadow + probe.rays.environmentShadow, 0) << "no emitters, no sky: no such rays";
  }
}

// sun_ground: the ground in the sun has L = 0.5/π · 3 · colour · cosθ with cosθ = 2/‖(−1, −2, −0.5)‖;
// with one reflection nothing else reaches it.
TEST(LightTransport, SunGroundRadianceIsLambertTimesTheSun) {
  REQUIRE_SHARED_DATA();
  const Scene scene = sharedScene("sun_ground");
  const RayTracer tracer(scene);
  TransportSettings settings;
  settings.bounces = 1;
  const PathIntegrator integrator(scene, tracer, settings);
  const Eigen::Vector3f directions[2] = {kDown, Eigen::Vector3f(0.3f, -1.0f, 0.2f).normalized()};
  Eigen::Vector3f radiance[2];
  float visibility[2];
  RayCounts counts;
  integrator.trace({-3, 0.25f, 2}, 0, directions, 2, radiance, visibility, &counts);  // far from the box
  const float cosTheta = 2.0f / Eigen::Vector3f(-1, -2, -0.5f).norm();
  const Eigen::Vector3f expected = Eigen::Vector3f(1.0f, 0.95f, 0.9f) * (0.5f / float(M_PI) * 3.0f * cosTheta);
  for (const Eigen::Vector3f& l : radiance)
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(l[c], expected[c], 1e-5f * expected[c]);
  EXPECT_EQ(visibility[0], 0.0f);
  EXPECT_EQ(counts.punctualShadow, 2);
}

// furnace: a closed cube emitting 1 with albedo 0.5 everywhere: with at most k reflections
// every direction brings L = (1 − ρ^(k+1))/(1 − ρ), so E(n) = πL for every normal.
TEST(LightTransport, FurnaceMatchesTheGeometricSeries) {
  REQUIRE_SHARED_DATA();
  const Scene scene = sharedScene("furnace");
  const RayTracer tracer(scene);
  const ShBasis basis(2);
  for (int k : {0, 1, 2, 3}) {
    const double expected = M_PI * (1.0 - std::pow(0.5, k + 1)) / 0.5;
    for (const Eigen::Vector3f& position : {Eigen::Vector3f(0, 0, 0), Eigen::Vector3f(0.5f, -0.3f, 0.2f)}) {
      const test::BakedProbe probe = test::bakeProbe(scene, tracer, basis, settingsWith(16384, k), position);
      for (const Eigen::Vector3f n : {Eigen::Vector3f(1, 0, 0), Eigen::Vector3f(0, -1, 0), Eigen::Vector3f(0, 0, 1)}) {
        EXPECT_NEAR(sampledIrradiance(probe.samples, n).x(), expected, 0.005 * expected) << "k = " << k;
        EXPECT_NEAR(basis.reconstruct(probe.coefficients.data(), n.cast<double>()).x(), expected, 0.005 * expected)
            << "k = " << k;
      }
      if (k == 0) EXPECT_EQ(probe.rays.bounce + probe.rays.emitterShadow, 0);
    }
  }
}

// alpha_fence: the fence is MASK with a checker of alpha 255 and 40 (cutoff 0.5). A ray passes
// the fence exactly where the texel it meets is transparent.
TEST(LightTransport, AlphaFencePassesExactlyTheTransparentTexels) {
  REQUIRE_SHARED_DATA();
  const Scene scene = sharedScene("alpha_fence");
  const RayTracer filtered(scene), unfiltered(scene, false);
  int crossings = 0, passed = 0;
  for (const Eigen::Vector3d& d : sphericalFibonacci(20000).directions) {
    const Eigen::Vector3f origin(0, 1, 1), direction = d.cast<float>();
    Hit first, filteredHit;
    unfiltered.intersect8(origin, &direction, 1, &first);
    if (first.missed() || !scene.material(first.instance, first.triangle).alphaTested()) continue;
    ++crossings;
    const float alpha =
        shadeSurface(scene, scene.instances[first.instance].mesh, first.triangle, first.u, first.v).alpha;
    filtered.intersect8(origin, &direction, 1, &filteredHit);
    const bool passes = filteredHit.missed() || filteredHit.distance > first.distance;
    EXPECT_EQ(passes, alpha < 0.5f) << "alpha " << alpha;
    EXPECT_TRUE(alpha > 0.9f || alpha < 0.2f) << "texels are 255 or 40, sampled without blending across them";
    passed += passes;
  }
  ASSERT_GT(crossings, 1000);
  EXPECT_NEAR(double(passed) / crossings, 0.5, 0.1) << "half the fence's texels are transparent";
}

// two_rooms: room A (x < 0) holds the lights; room B sees only what comes through the 1 × 2 m
// doorway. Closing the doorway with one more quad must leave room B's probes exactly black.
TEST(LightTransport, TwoRoomsLeakNothingButThroughTheDoorway) {
  REQUIRE_SHARED_DATA();
  const std::string dir = test::makeTempDir("two_rooms_closed");
  const std::string source = test::sharedDataPath("scenes/two_rooms/");
  std::filesystem::copy_file(source + "two_rooms.bin", dir + "/two_rooms.bin");
  nlohmann::json gltf = nlohmann::json::parse(std::ifstream(source + "two_rooms.gltf"));
  // The wall between the rooms is x = 0; the doorway spans z ∈ [−0.5, 0.5], y ∈ [0, 2]. The
  // blocker overlaps the wall around it.
  const std::vector<float> quad = {0, -0.1f, -0.7f, 0, 2.2f, -0.7f, 0, 2.2f, 0.7f, 0, -0.1f, 0.7f};
  const std::vector<std::uint32_t> indices = {0, 1, 2, 0, 2, 3};
  // Copied into place: GCC 12 warned of an over-read (-Wstringop-overread, a false alarm) on the
  // same bytes appended with vector::insert.
  std::vector<unsigned char> bytes(72);
  std::memcpy(bytes.data(), quad.data(), 48);
  std::memcpy(bytes.data() + 48, indices.data(), 24);
  const int buffer = int(gltf["buffers"].size());
  gltf["buffers"].push_back({{"byteLength", 72}, {"uri", "data:application/octet-stream;base64," + test::base64(bytes)}});
  const int view = int(gltf["bufferViews"].size());
  gltf["bufferViews"].push_back({{"buffer", buffer}, {"byteOffset", 0}, {"byteLength", 48}});
  gltf["bufferViews"].push_back({{"buffer", buffer}, {"byteOffset", 48}, {"byteLength", 24}});
  const int accessor = int(gltf["accessors"].size());
  gltf["accessors"].push_back({{"bufferView", view}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"},
                               {"min", {0, -0.1, -0.7}}, {"max", {0, 2.2, 0.7}}});
  gltf["accessors"].push_back({{"bufferView", view + 1}, {"componentType", 5125}, {"count", 6}, {"type", "SCALAR"}});
  gltf["meshes"].push_back(
      {{"primitives", {{{"attributes", {{"POSITION", accessor}}}, {"indices", accessor + 1}, {"material", 0}}}}});
  gltf["nodes"].push_back({{"mesh", int(gltf["meshes"].size()) - 1}});
  gltf["scenes"][0]["nodes"].push_back(int(gltf["nodes"].size()) - 1);
  std::ofstream(dir + "/two_rooms.gltf") << gltf.dump();

  const Scene open = sharedScene("two_rooms");
  const Scene closed = loadGltf(dir + "/two_rooms.gltf");
  const RayTracer openTracer(open), closedTracer(closed);
  const ShBasis basis(2);
  for (const Eigen::Vector3f& roomB : {Eigen::Vector3f(2, 1.5f, 0), Eigen::Vector3f(3.5f, 1.5f, 1.5f)}) {
    const test::BakedProbe lit = test::bakeProbe(open, openTracer, basis, settingsWith(4096, 3), roomB);
    const test::BakedProbe dark = test::bakeProbe(closed, closedTracer, basis, settingsWith(4096, 3), roomB);
    double litTotal = 0.0;
    for (std::size_t r = 0; r < dark.samples.radiance.size(); ++r) {
      EXPECT_EQ(dark.samples.radiance[r], Eigen::Vector3f::Zero()) << "light leaked into the closed room B";
      litTotal += lit.samples.radiance[r].sum();
    }
    EXPECT_TRUE(dark.samples.punctual.empty());
    EXPECT_GT(litTotal, 0.0) << "the doorway lets light into room B";
  }
}

}  // namespace
}  // namespace baker
