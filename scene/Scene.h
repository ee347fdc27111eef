#pragma once
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <string>
#include <vector>

namespace baker {

struct Material {
  std::string name;
  Eigen::Vector3f baseColor{1.0f, 1.0f, 1.0f};
  // Emitted radiance: emissiveFactor × KHR_materials_emissive_strength.
  Eigen::Vector3f emission{0.0f, 0.0f, 0.0f};
  bool doubleSided = false;
};

// The whole glTF scene flattened into world space: one triangle soup with a material per
// triangle. Everything downstream (BVH, baking) reads only this.
struct Scene {
  std::string sourcePath;
  std::vector<Eigen::Vector3f> positions;
  std::vector<Eigen::Vector3i> triangles;     // indices into positions, counter-clockwise = front
  std::vector<std::uint32_t> triangleMaterial;  // index into materials, one per triangle
  std::vector<Material> materials;
  Eigen::AlignedBox3f bounds;                 // empty when the scene has no triangles
  std::vector<std::string> warnings;          // things skipped or assumed while loading

  bool hasEmission() const {
    for (const Material& m : materials)
      if (m.emission.maxCoeff() > 0.0f) return true;
    return false;
  }
};

}  // namespace baker
