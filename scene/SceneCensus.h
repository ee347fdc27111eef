#pragma once
#include <cstdint>
#include <vector>

#include "scene/Scene.h"

namespace baker {

// What a loaded scene holds, counted once. Triangle counts are in world space: a mesh placed
// by three nodes counts three times.
struct SceneCensus {
  std::uint64_t triangles = 0;
  std::uint64_t uniqueTriangles = 0;  // each mesh once
  std::size_t instancedMeshes = 0;    // meshes placed by more than one node
  std::vector<bool> materialInUse;    // by Scene::materials index: some triangle uses it
  std::size_t materialsInUse = 0;
  // The file's own materials (not the default one) by alpha mode: OPAQUE, MASK, BLEND.
  std::size_t materialsByAlphaMode[3] = {0, 0, 0};
  std::size_t doubleSidedMaterials = 0;
  std::size_t texturedMaterials = 0;  // base colour or emissive texture decoded
  std::uint64_t emissiveTriangles = 0;
  std::uint64_t reflectiveTriangles = 0;  // non-zero base colour factor
  std::uint64_t alphaTestedTriangles = 0;
  std::size_t lightsByType[3] = {0, 0, 0};  // point, spot, directional
  std::uint64_t textureTexels = 0;
  std::size_t textureBytes = 0;
};

SceneCensus takeCensus(const Scene& scene);

}  // namespace baker
