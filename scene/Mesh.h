#pragma once
#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

namespace baker {

// The triangles of one glTF mesh (all its primitives) with the vertex attributes shading
// reads. Positions are in the mesh's object space, except for skinned meshes, which are posed
// in world space (their instance transform is the identity).
struct Mesh {
  std::string source;  // the glTF path, e.g. "meshes[3]", for messages
  std::vector<Eigen::Vector3f> positions;
  std::vector<Eigen::Vector3i> triangles;       // counter-clockwise = front, in object space
  std::vector<std::uint32_t> triangleMaterial;  // index into Scene::materials
  // Triangles [alphaTestedBegin, size) have MASK or BLEND materials, the others OPAQUE, so
  // the tracer can put alpha filters on exactly the triangles that need them.
  std::uint32_t alphaTestedBegin = 0;
  // texcoords[n] is TEXCOORD_n per vertex, kept only for sets some material reads (others
  // are empty); a primitive without a set that another primitive has reads (0, 0).
  std::vector<std::vector<Eigen::Vector2f>> texcoords;
  // COLOR_0 per vertex as linear RGBA; empty when no primitive has it (white).
  std::vector<Eigen::Vector4f> colors;

  std::size_t triangleCount() const { return triangles.size(); }
};

}  // namespace baker
