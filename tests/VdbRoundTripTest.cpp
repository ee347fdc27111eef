#include <gtest/gtest.h>

#include <algorithm>

#include <filesystem>
#include <random>

#include "bake/Baker.h"
#include "basis/BasisRegistry.h"
#include "formats/VdbWriter.h"
#include "formats/VolumeReader.h"
#include "scene/GltfLoader.h"
#include "scene/RayTracer.h"
#include "tests/TestData.h"

namespace baker {
namespace {

void expectSameVolume(const Volume& a, const Volume& b) {
  EXPECT_EQ(a.basisName, b.basisName);
  EXPECT_EQ(a.grid.dims, b.grid.dims);
  EXPECT_EQ(a.grid.origin, b.grid.origin);
  EXPECT_EQ(a.grid.spacing, b.grid.spacing);
  EXPECT_EQ(a.settings, b.settings);
  ASSERT_EQ(a.coefficients.size(), b.coefficients.size());
  for (std::size_t i = 0; i < a.coefficients.size(); ++i)
    ASSERT_EQ(a.coefficients[i], b.coefficients[i]) << "coefficient " << i;  // bit-exact in float
  EXPECT_EQ(a.visibilityPerProbe, b.visibilityPerProbe);
  EXPECT_TRUE(a.visibility == b.visibility);
  EXPECT_TRUE(a.states == b.states);
  EXPECT_TRUE(a.offsets == b.offsets);
}

TEST(VdbRoundTrip, RandomCoefficientsReadBackIdentical) {
  const auto basis = makeBasis("sh-l2");
  Volume v;
  v.grid.dims = Eigen::Vector3i(9, 3, 17);  // crosses brick and leaf boundaries unevenly
  v.grid.origin = Eigen::Vector3d(-1.25, 0.5, 3.0);
  v.grid.spacing = 0.37;
  v.basisName = basis->name();
  v.coefficientsPerProbe = basis->totalCoefficients();
  v.settings = {{"rays", "64"}, {"scene", "random.gltf"}};
  std::mt19937 rng(3);
  std::normal_distribution<float> normal(0.0f, 10.0f);
  v.coefficients.resize(std::size_t(v.grid.probeCount()) * v.coefficientsPerProbe);
  for (float& c : v.coefficients) c = normal(rng);
  v.coefficients[5] = 0.0f;  // background value must survive too

  const std::string path = test::makeTempDir("vdb") + "/random.vdb";
  writeVdb(v, *basis, path);
  expectSameVolume(v, readVolume(path));
}

TEST(VdbRoundTrip, DefaultSceneBakeReadsBackIdentical) {
  const Scene scene = loadGltf(test::sourcePath("data/default_room/default_room.gltf"));
  const RayTracer tracer(scene);
  const auto basis = makeBasis("sh-l2");
  const ProbeGrid grid = makeProbeGrid(scene.bounds, 0.5, 1 << 20);
  BakeSettings settings;
  settings.rays = 64;
  Volume v = bakeVolume(scene, tracer, *basis, grid, settings, nullptr);
  float largest = 0.0f;
  for (float c : v.coefficients) largest = std::max(largest, std::abs(c));
  EXPECT_GT(largest, 0.1f) << "the emissive panel must show up in the bake";
  // The room has furniture: some probes sit inside it and are moved or filled.
  EXPECT_GT(std::count(v.states.begin(), v.states.end(), ProbeState::Relocated) +
                std::count(v.states.begin(), v.states.end(), ProbeState::Invalid),
            0);
  EXPECT_EQ(v.visibilityPerProbe, 9);
  const std::string path = test::makeTempDir("vdb-default") + "/room.vdb";
  writeVdb(v, *basis, path);
  expectSameVolume(v, readVolume(path));
}

}  // namespace
}  // namespace baker
