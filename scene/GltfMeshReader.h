#pragma once
#include <tiny_gltf.h>

#include <Eigen/Core>
#include <string>
#include <vector>

#include "scene/GltfMaterials.h"
#include "scene/Mesh.h"

namespace baker {

// The default pose of one use of a mesh. Morph targets move POSITION by Σ weight × target; a
// skinned mesh is then posed by linear blend skinning with the joints where their nodes stand.
struct MeshPose {
  std::vector<double> morphWeights;            // by target; empty or all zero: the base shape
  std::vector<Eigen::Matrix4d> jointMatrices;  // world(joint) × inverseBindMatrix; empty: not skinned
};

// Reads glTF meshes into Meshes: TRIANGLES, TRIANGLE_STRIP and TRIANGLE_FAN primitives (points
// and lines are skipped), every index and component type, sparse accessors, quantized
// attributes (KHR_mesh_quantization), the TEXCOORD_n sets materials read and COLOR_0. Problems
// a user must fix are InputErrors naming the file and glTF path; what the reader can step over
// (degenerate triangles, skipped modes, a missing texcoord set, COLOR_0 outside [0, 1] or NaN,
// which is clamped) becomes one warning per kind.
class GltfMeshReader {
 public:
  // Geometry in the whole scene beyond these many vertices or triangles is refused before it
  // is read: bounded memory whatever the file's counts say.
  static constexpr std::size_t kMaxVertices = std::size_t(1) << 26;
  static constexpr std::size_t kMaxTriangles = std::size_t(1) << 26;

  GltfMeshReader(const tinygltf::Model& model, const std::string& file, const GltfMaterials& materials);

  Mesh read(int meshIndex, const MeshPose& pose);
  // One line per kind of thing stepped over so far.
  std::vector<std::string> warnings() const;

 private:
  // Triangles collected per primitive, opaque ones and alpha-tested ones apart.
  struct TriangleLists {
    std::vector<Eigen::Vector3i> triangles[2];
    std::vector<std::uint32_t> materials[2];
  };
  struct Skipped {
    std::size_t count = 0;
    std::string first;
    void note(std::size_t n, const std::string& where) {
      if (count == 0 && n > 0) first = where;
      count += n;
    }
  };

  void readPrimitive(int meshIndex, int primitiveIndex, const MeshPose& pose, Mesh& mesh, TriangleLists& lists);
  // TEXCOORD_n of the sets materials read, and COLOR_0, of the primitive's vertices (from
  // `base` in the mesh). Attributes stay empty until a primitive has them; the vertices of
  // primitives without them then get the default (uv (0, 0), white).
  void readTexcoordsAndColors(const tinygltf::Primitive& prim, const std::string& path, std::size_t base,
                              std::size_t vertexCount, std::uint32_t material, Mesh& mesh);
  // The primitive's indices, each checked against the vertex count; 0, 1, 2, ... without any.
  std::vector<std::uint32_t> readIndices(const tinygltf::Primitive& prim, const std::string& path,
                                         std::size_t vertexCount);
  std::vector<Eigen::Vector3f> readPositions(const tinygltf::Primitive& prim, const std::string& path,
                                             const MeshPose& pose);
  // Attribute `name` as floats, `components` per vertex (between min and max), or empty when
  // the primitive has none. Its count must match the vertex count.
  std::vector<float> readAttribute(const tinygltf::Primitive& prim, const std::string& name, std::size_t vertices,
                                   const std::string& path, int minComponents, int maxComponents, int* components);
  std::uint32_t materialOf(const tinygltf::Primitive& prim, const std::string& path) const;
  void skin(std::vector<Eigen::Vector3d>& positions, const tinygltf::Primitive& prim, const std::string& path,
            const MeshPose& pose);

  const tinygltf::Model& model_;
  std::string file_;
  const GltfMaterials& materials_;
  std::size_t vertices_ = 0;
  std::size_t triangles_ = 0;
  Skipped degenerate_, points_, lines_, missingTexcoords_, outOfRangeColors_;
};

}  // namespace baker
