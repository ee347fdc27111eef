#pragma once
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <string>
#include <vector>

#include "scene/ColorImage.h"
#include "scene/Environment.h"
#include "scene/Material.h"
#include "scene/Mesh.h"
#include "scene/PunctualLight.h"

namespace baker {

// One placement of a mesh by a node. A triangle of the whole scene is (instance, triangle of
// its mesh); its global id is firstTriangle + that triangle.
struct Instance {
  std::uint32_t mesh = 0;
  int node = -1;                    // the glTF node
  Eigen::Matrix4f objectToWorld = Eigen::Matrix4f::Identity();
  // Maps object-space normals to world space, keeping glTF's front side in front under
  // mirroring: the inverse transpose of the linear part (not the cofactor, whose sign flips).
  Eigen::Matrix3f normalToWorld = Eigen::Matrix3f::Identity();
  std::uint64_t firstTriangle = 0;
};

// The scene description a bake reads: the glTF default scene (or the one chosen) with its
// meshes, instances, materials, decoded textures and lights, plus the environment given on the
// command line. Everything downstream (BVH, shading, baking) reads only this.
struct Scene {
  std::string sourcePath;
  int sceneIndex = -1;  // the glTF scene loaded; -1 when the file has none
  int sceneCount = 0;   // scenes the file defines
  std::vector<Mesh> meshes;
  std::vector<Instance> instances;
  std::vector<Material> materials;  // the glTF materials in order, then the default material
  std::vector<ColorImage> images;   // decoded colour textures, referenced by TextureSlot::image
  std::vector<PunctualLight> lights;
  Environment environment;
  Eigen::AlignedBox3f bounds;  // of all instanced triangles in world space; empty when none
  std::vector<std::string> extensionsUsed;     // the file's extensionsUsed
  std::vector<std::string> extensionsIgnored;  // those of them this baker does not apply
  std::vector<std::string> warnings;           // things skipped or assumed while loading
  // World positions the file suggests for probes (scenes[i].extras.probe_hint: [[x, y, z], …]),
  // where its author knows something about the light; empty when it suggests none.
  std::vector<Eigen::Vector3f> probeHints;

  // Triangles in world space, counting each instance of a mesh.
  std::uint64_t triangleCount() const;
  std::uint64_t globalTriangle(std::uint32_t instance, std::uint32_t triangle) const {
    return instances[instance].firstTriangle + triangle;
  }
  const Material& material(std::uint32_t instance, std::uint32_t triangle) const {
    return materials[meshes[instances[instance].mesh].triangleMaterial[triangle]];
  }
  // World-space unit normal of the side glTF calls front (counter-clockwise in object space).
  Eigen::Vector3f frontNormal(std::uint32_t instance, std::uint32_t triangle) const;
};

}  // namespace baker
