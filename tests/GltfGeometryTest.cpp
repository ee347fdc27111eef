#include <gtest/gtest.h>

#include <cstring>

#include "common/Error.h"
#include "scene/GltfLoader.h"
#include "scene/RayTracer.h"
#include "tests/GltfTestAssets.h"
#include "tests/TestData.h"

namespace baker {
namespace {

using test::GltfBuilder;

class GltfGeometry : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = test::makeTempDir(::testing::UnitTest::GetInstance()->current_test_info()->name()); }
  Scene load(const GltfBuilder& gltf, const SceneOptions& options = {}) {
    return loadGltf(gltf.write(dir_, "scene"), options);
  }
  bool warned(const Scene& scene, const std::string& needle) {
    for (const std::string& w : scene.warnings)
      if (w.find(needle) != std::string::npos) return true;
    return false;
  }
  std::string dir_;
};

Eigen::Vector3f worldVertex(const Scene& scene, std::size_t instance, std::size_t vertex) {
  const Instance& inst = scene.instances[instance];
  return (inst.objectToWorld * scene.meshes[inst.mesh].positions[vertex].homogeneous()).head<3>();
}

TEST_F(GltfGeometry, MeshUsedByThreeNodesIsReadOnceAndInstanced) {
  GltfBuilder gltf;
  const int mesh = gltf.mesh({{"POSITION", gltf.floats(test::triangleXY(), "VEC3")}});
  for (int k = 0; k < 3; ++k) gltf.node({{"mesh", mesh}, {"translation", {2.0 * k, 0, 0}}});
  const Scene scene = load(gltf);
  ASSERT_EQ(scene.meshes.size(), 1u);
  ASSERT_EQ(scene.instances.size(), 3u);
  EXPECT_EQ(scene.triangleCount(), 3u);
  EXPECT_EQ(scene.bounds.min(), Eigen::Vector3f(0, 0, 0));
  EXPECT_EQ(scene.bounds.max(), Eigen::Vector3f(5, 1, 0));

  const RayTracer tracer(scene);
  EXPECT_EQ(tracer.instancedMeshes(), 1);
  // One ray down onto each instance: the hit names the instance and a distinct global triangle.
  for (std::uint32_t k = 0; k < 3; ++k) {
    const Eigen::Vector3f down(0, 0, -1);
    Hit hit;
    tracer.intersect8(Eigen::Vector3f(2.0f * k + 0.25f, 0.25f, 1.0f), &down, 1, &hit);
    ASSERT_FALSE(hit.missed());
    EXPECT_EQ(hit.instance, k);
    EXPECT_EQ(hit.triangle, 0u);
    EXPECT_EQ(scene.globalTriangle(hit.instance, hit.triangle), k);
    EXPECT_TRUE(hit.frontFace);
    EXPECT_FLOAT_EQ(hit.distance, 1.0f);
    EXPECT_NEAR(hit.u, 0.25f, 1e-6f);
    EXPECT_NEAR(hit.v, 0.25f, 1e-6f);
  }
}

// UNSIGNED_BYTE and UNSIGNED_SHORT indices (UNSIGNED_INT is what the builder writes elsewhere).
TEST_F(GltfGeometry, EveryIndexTypeReadsTheSameTriangles) {
  for (int componentType : {5121, 5123, 5125}) {
    GltfBuilder gltf;
    const int size = componentType == 5121 ? 1 : componentType == 5123 ? 2 : 4;
    std::vector<std::uint8_t> bytes;
    for (std::uint32_t index : {2u, 1u, 0u})  // reversed: the order must survive
      for (int b = 0; b < size; ++b) bytes.push_back(std::uint8_t(index >> (8 * b)));
    const int indices = gltf.raw(bytes, componentType, "SCALAR", 3, false);
    gltf.node({{"mesh", gltf.mesh({{"POSITION", gltf.floats(test::triangleXY(), "VEC3")}}, indices)}});
    const Scene scene = load(gltf);
    ASSERT_EQ(scene.triangleCount(), 1u) << "componentType " << componentType;
    EXPECT_EQ(scene.meshes[0].triangles[0], Eigen::Vector3i(2, 1, 0)) << "componentType " << componentType;
  }
}

TEST_F(GltfGeometry, MatrixTrsAndHierarchyCompose) {
  GltfBuilder gltf;
  const int mesh = gltf.mesh({{"POSITION", gltf.floats(test::triangleXY(), "VEC3")}});
  // Column-major translation by (10, 0, 0), then a child rotated 90° about +Z and scaled by 2.
  const int child = gltf.node({{"mesh", mesh}, {"rotation", {0, 0, std::sqrt(0.5), std::sqrt(0.5)}}, {"scale", {2, 2, 2}}},
                              false);
  gltf.node({{"matrix", {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 10, 0, 0, 1}}, {"children", {child}}});
  const Scene scene = load(gltf);
  ASSERT_EQ(scene.instances.size(), 1u);
  EXPECT_TRUE(worldVertex(scene, 0, 1).isApprox(Eigen::Vector3f(10, 2, 0), 1e-6f));   // (1,0,0) → (0,2,0) + (10,0,0)
  EXPECT_TRUE(worldVertex(scene, 0, 2).isApprox(Eigen::Vector3f(8, 0, 0), 1e-6f));    // (0,1,0) → (−2,0,0) + (10,0,0)
}

TEST_F(GltfGeometry, MirroredTransformKeepsTheFrontFace) {
  GltfBuilder gltf;
  const int mesh = gltf.mesh({{"POSITION", gltf.floats(test::triangleXY(), "VEC3")}});
  gltf.node({{"mesh", mesh}, {"scale", {-1, 1, 1}}});
  const Scene scene = load(gltf);
  const RayTracer tracer(scene);
  const Eigen::Vector3f down(0, 0, -1), up(0, 0, 1);
  Hit hit;
  tracer.intersect8(Eigen::Vector3f(-0.25f, 0.25f, 1.0f), &down, 1, &hit);
  ASSERT_FALSE(hit.missed());
  EXPECT_TRUE(hit.frontFace) << "a mirrored node must not turn its front faces into back faces";
  tracer.intersect8(Eigen::Vector3f(-0.25f, 0.25f, -1.0f), &up, 1, &hit);
  ASSERT_FALSE(hit.missed());
  EXPECT_FALSE(hit.frontFace);
  EXPECT_TRUE(scene.frontNormal(0, 0).isApprox(Eigen::Vector3f(0, 0, 1)));
}

TEST_F(GltfGeometry, SceneOptionPicksTheGltfScene) {
  GltfBuilder gltf;
  const int mesh = gltf.mesh({{"POSITION", gltf.floats(test::triangleXY(), "VEC3")}});
  gltf.node({{"mesh", mesh}});                                                   // scene 0
  const int far = gltf.node({{"mesh", mesh}, {"translation", {0, 0, 7}}}, false);  // scene 1
  gltf.json()["scenes"].push_back({{"nodes", {far}}});
  gltf.json()["scene"] = 1;
  EXPECT_EQ(load(gltf).bounds.max().z(), 7.0f) << "the default scene is the file's \"scene\"";
  SceneOptions first;
  first.scene = 0;
  const Scene scene0 = load(gltf, first);
  EXPECT_EQ(scene0.sceneIndex, 0);
  EXPECT_EQ(scene0.sceneCount, 2);
  EXPECT_EQ(scene0.bounds.max().z(), 0.0f);
  SceneOptions missing;
  missing.scene = 2;
  try {
    load(gltf, missing);
    FAIL() << "scene 2 does not exist";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("scene 2: "), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("scene.gltf"), std::string::npos) << e.what();
  }
}

TEST_F(GltfGeometry, QuantizedPositionsDecode) {
  GltfBuilder gltf;
  // KHR_mesh_quantization: normalised SHORT positions (32767 = 1) and plain UNSIGNED_BYTE ones.
  const std::int16_t s[9] = {0, 0, 0, 32767, 0, 0, 0, -32767, 0};
  std::vector<std::uint8_t> shortBytes(sizeof s);
  std::memcpy(shortBytes.data(), s, sizeof s);
  // VEC3 of SHORT is 6 bytes; glTF wants 4-byte aligned elements for vertex attributes, so the
  // quantized positions use byteStride 8.
  std::vector<std::uint8_t> strided(24, 0);
  for (int v = 0; v < 3; ++v) std::memcpy(&strided[8 * v], &shortBytes[6 * v], 6);
  const int pos16 = gltf.raw(strided, 5122, "VEC3", 3, true);
  gltf.json()["bufferViews"][gltf.json()["accessors"][pos16]["bufferView"].get<int>()]["byteStride"] = 8;
  const int pos8 = gltf.raw({0, 0, 0, 0, 200, 0, 0, 0, 0, 100, 0, 0}, 5121, "VEC3", 3, false);
  gltf.json()["bufferViews"][gltf.json()["accessors"][pos8]["bufferView"].get<int>()]["byteStride"] = 4;
  gltf.node({{"mesh", gltf.mesh({{"POSITION", pos16}})}, {"scale", {4, 4, 4}}});
  gltf.node({{"mesh", gltf.mesh({{"POSITION", pos8}})}, {"scale", {0.01, 0.01, 0.01}}});
  gltf.json()["extensionsUsed"] = {"KHR_mesh_quantization"};
  gltf.json()["extensionsRequired"] = {"KHR_mesh_quantization"};
  const Scene scene = load(gltf);
  ASSERT_EQ(scene.instances.size(), 2u);
  EXPECT_TRUE(worldVertex(scene, 0, 1).isApprox(Eigen::Vector3f(4, 0, 0)));
  EXPECT_TRUE(worldVertex(scene, 0, 2).isApprox(Eigen::Vector3f(0, -4, 0)));
  EXPECT_TRUE(worldVertex(scene, 1, 1).isApprox(Eigen::Vector3f(2, 0, 0)));
  EXPECT_TRUE(worldVertex(scene, 1, 2).isApprox(Eigen::Vector3f(0, 1, 0)));
  EXPECT_TRUE(scene.extensionsIgnored.empty());
}

TEST_F(GltfGeometry, SparseAccessorSubstitutesVertices) {
  GltfBuilder gltf;
  const int pos = gltf.floats(test::triangleXY(), "VEC3");
  const int sparseIndices = gltf.indices({2});
  const int sparseValues = gltf.floats({0, 3, 0}, "VEC3");
  auto& accessor = gltf.json()["accessors"][pos];
  accessor["sparse"] = {{"count", 1},
                        {"indices", {{"bufferView", gltf.json()["accessors"][sparseIndices]["bufferView"]}, {"componentType", 5125}}},
                        {"values", {{"bufferView", gltf.json()["accessors"][sparseValues]["bufferView"]}}}};
  gltf.node({{"mesh", gltf.mesh({{"POSITION", pos}})}});
  const Scene scene = load(gltf);
  EXPECT_EQ(scene.bounds.max().y(), 3.0f);
}

TEST_F(GltfGeometry, StripsFansAndSkippedModes) {
  GltfBuilder gltf;
  const int square = gltf.floats({0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0}, "VEC3");
  auto add = [&](int mode) {
    const int mesh = gltf.mesh({{"POSITION", square}});
    gltf.json()["meshes"][mesh]["primitives"][0]["mode"] = mode;
    gltf.node({{"mesh", mesh}});
  };
  add(5);  // strip: 2 triangles, both facing +Z
  add(6);  // fan around vertex 0: (0,1,2) facing +Z, (0,2,3) facing −Z
  add(0);  // points
  add(1);  // lines
  add(3);  // line strip
  const Scene scene = load(gltf);
  EXPECT_EQ(scene.triangleCount(), 4u);
  EXPECT_TRUE(scene.frontNormal(0, 0).isApprox(Eigen::Vector3f(0, 0, 1)));
  EXPECT_TRUE(scene.frontNormal(0, 1).isApprox(Eigen::Vector3f(0, 0, 1)));
  EXPECT_TRUE(warned(scene, "skipped 1 primitive(s) of points (first: meshes[2].primitives[0])"));
  EXPECT_TRUE(warned(scene, "skipped 2 primitive(s) of lines (first: meshes[3].primitives[0])"));
}

TEST_F(GltfGeometry, DegenerateTrianglesAreSkippedWithOneWarning) {
  GltfBuilder gltf;
  const int pos = gltf.floats({0, 0, 0, 1, 0, 0, 0, 1, 0, 2, 0, 0}, "VEC3");
  // Triangle 1 repeats a vertex, triangle 2 is collinear.
  gltf.node({{"mesh", gltf.mesh({{"POSITION", pos}}, gltf.indices({0, 1, 2, 0, 0, 1, 0, 1, 3}))}});
  const Scene scene = load(gltf);
  EXPECT_EQ(scene.triangleCount(), 1u);
  EXPECT_TRUE(warned(scene, "skipped 2 degenerate triangle(s) of zero area (first: meshes[0].primitives[0] (triangle 1))"));
}

TEST_F(GltfGeometry, MorphTargetsUseTheDefaultWeights) {
  GltfBuilder gltf;
  const int pos = gltf.floats(test::triangleXY(), "VEC3");
  const int delta = gltf.floats({0, 0, 2, 0, 0, 2, 0, 0, 2}, "VEC3");
  const int mesh = gltf.mesh({{"POSITION", pos}});
  gltf.json()["meshes"][mesh]["primitives"][0]["targets"] = {{{"POSITION", delta}}};
  gltf.json()["meshes"][mesh]["weights"] = {0.25};
  gltf.node({{"mesh", mesh}});
  gltf.node({{"mesh", mesh}, {"weights", {1.0}}});  // its own weights: its own copy of the mesh
  const Scene scene = load(gltf);
  ASSERT_EQ(scene.meshes.size(), 2u);
  EXPECT_FLOAT_EQ(worldVertex(scene, 0, 0).z(), 0.5f);
  EXPECT_FLOAT_EQ(worldVertex(scene, 1, 0).z(), 2.0f);
  EXPECT_TRUE(warned(scene, "2 mesh instance(s) with morph targets (first: nodes[0]) at their default weights"));
}

TEST_F(GltfGeometry, SkinnedMeshTakesItsRestPose) {
  GltfBuilder gltf;
  const int pos = gltf.floats(test::triangleXY(), "VEC3");
  // Vertex 2 follows joint 1 alone; vertices 0 and 1 joint 0. Joint 1 stands 5 up, with an
  // inverse bind matrix of identity; joint 0 stands at the origin.
  const int joints = gltf.raw({0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0}, 5121, "VEC4", 3, false);
  const int weights = gltf.floats({1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0}, "VEC4");
  const int mesh = gltf.mesh({{"POSITION", pos}, {"JOINTS_0", joints}, {"WEIGHTS_0", weights}});
  const int j1 = gltf.node({{"translation", {0, 5, 0}}}, false);
  const int j0 = gltf.node({{"children", {j1}}});
  // The skinned node's own transform is ignored by glTF.
  gltf.node({{"mesh", mesh}, {"skin", 0}, {"translation", {100, 0, 0}}});
  gltf.json()["skins"] = {{{"joints", {j0, j1}}}};
  const Scene scene = load(gltf);
  ASSERT_EQ(scene.instances.size(), 1u);
  EXPECT_TRUE(worldVertex(scene, 0, 1).isApprox(Eigen::Vector3f(1, 0, 0)));
  EXPECT_TRUE(worldVertex(scene, 0, 2).isApprox(Eigen::Vector3f(0, 6, 0)));
  EXPECT_TRUE(warned(scene, "1 skinned mesh instance(s) (first: nodes[2]) in their rest pose"));
}

TEST_F(GltfGeometry, ExternalBufferAndGlbLoadAlike) {
  GltfBuilder gltf;
  gltf.node({{"mesh", gltf.mesh({{"POSITION", gltf.floats(test::triangleXY(3.0f), "VEC3")}})}});
  EXPECT_EQ(loadGltf(gltf.write(dir_, "external", true)).bounds.max(), Eigen::Vector3f(3, 3, 0));
  EXPECT_EQ(loadGltf(gltf.writeGlb(dir_, "binary")).bounds.max(), Eigen::Vector3f(3, 3, 0));
}

}  // namespace
}  // namespace baker
