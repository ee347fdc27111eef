#include "scene/GltfMeshReader.h"

#include <fmt/format.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "common/Error.h"
#include "scene/GltfAccessor.h"

namespace baker {
namespace {

// Triangles a primitive of `indexCount` indices makes in `mode` (an upper bound for the budget).
std::size_t trianglesOf(int mode, std::size_t indexCount) {
  if (mode == TINYGLTF_MODE_TRIANGLES) return indexCount / 3;
  return indexCount >= 3 ? indexCount - 2 : 0;
}

// glTF keeps COLOR_0 within [0, 1], but a float attribute can hold anything: a colour above 1
// would reflect more light than arrives, and NaN would spread through every path that meets
// it. Such components are clamped, NaN reads as 1 (a vertex without COLOR_0). True if any was.
bool sanitizeColor(Eigen::Vector4f& color) {
  const Eigen::Vector4f clean = color.unaryExpr([](float c) { return std::isnan(c) ? 1.0f : std::clamp(c, 0.0f, 1.0f); });
  const bool changed = !(clean.array() == color.array()).all();
  color = clean;
  return changed;
}

bool readsSet(const Material& m, int set) {
  return (m.baseColorTexture.present() && m.baseColorTexture.texCoord == set) ||
         (m.emissiveTexture.present() && m.emissiveTexture.texCoord == set);
}

}  // namespace

GltfMeshReader::GltfMeshReader(const tinygltf::Model& model, const std::string& file, const GltfMaterials& materials)
    : model_(model), file_(file), materials_(materials) {}

Mesh GltfMeshReader::read(int meshIndex, const MeshPose& pose) {
  const tinygltf::Mesh& src = model_.meshes[meshIndex];
  Mesh mesh;
  mesh.source = fmt::format("meshes[{}]", meshIndex);
  mesh.texcoords.resize(materials_.texcoordSets.empty() ? 0 : *materials_.texcoordSets.rbegin() + 1);
  TriangleLists lists;
  for (std::size_t p = 0; p < src.primitives.size(); ++p) readPrimitive(meshIndex, int(p), pose, mesh, lists);
  // Primitives after the last one with an attribute still need its default.
  for (std::vector<Eigen::Vector2f>& set : mesh.texcoords)
    if (!set.empty()) set.resize(mesh.positions.size(), Eigen::Vector2f::Zero());
  if (!mesh.colors.empty()) mesh.colors.resize(mesh.positions.size(), Eigen::Vector4f::Ones());
  mesh.triangles = std::move(lists.triangles[0]);
  mesh.triangleMaterial = std::move(lists.materials[0]);
  mesh.alphaTestedBegin = std::uint32_t(mesh.triangles.size());
  mesh.triangles.insert(mesh.triangles.end(), lists.triangles[1].begin(), lists.triangles[1].end());
  mesh.triangleMaterial.insert(mesh.triangleMaterial.end(), lists.materials[1].begin(), lists.materials[1].end());
  return mesh;
}

void GltfMeshReader::readPrimitive(int meshIndex, int primitiveIndex, const MeshPose& pose, Mesh& mesh,
                                   TriangleLists& lists) {
  const tinygltf::Primitive& prim = model_.meshes[meshIndex].primitives[primitiveIndex];
  const std::string path = fmt::format("meshes[{}].primitives[{}]", meshIndex, primitiveIndex);
  switch (prim.mode) {
    case TINYGLTF_MODE_POINTS: points_.note(1, path); return;
    case TINYGLTF_MODE_LINE: case TINYGLTF_MODE_LINE_LOOP: case TINYGLTF_MODE_LINE_STRIP: lines_.note(1, path); return;
    case TINYGLTF_MODE_TRIANGLES: case TINYGLTF_MODE_TRIANGLE_STRIP: case TINYGLTF_MODE_TRIANGLE_FAN: break;
    default: throw InputError(fmt::format("{}: {}.mode {} is not a glTF primitive mode (0-6)", file_, path, prim.mode));
  }
  const auto pos = prim.attributes.find("POSITION");
  if (pos == prim.attributes.end()) throw InputError(fmt::format("{}: {}.attributes has no POSITION", file_, path));
  // Budget first, from the counts alone, so nothing is allocated for a scene beyond it.
  const std::size_t vertexCount = GltfAccessor(model_, pos->second, file_, path + ".attributes.POSITION").count();
  const std::size_t indexCount =
      prim.indices >= 0 ? GltfAccessor(model_, prim.indices, file_, path + ".indices").count() : vertexCount;
  vertices_ += vertexCount;
  triangles_ += trianglesOf(prim.mode, indexCount);
  if (vertices_ > kMaxVertices || triangles_ > kMaxTriangles)
    throw InputError(fmt::format("{}: {} brings the scene to {} vertices and {} triangles, beyond the limit of {} each",
                                 file_, path, vertices_, triangles_, kMaxVertices));

  const std::vector<Eigen::Vector3f> positions = readPositions(prim, path, pose);
  const std::size_t base = mesh.positions.size();
  mesh.positions.insert(mesh.positions.end(), positions.begin(), positions.end());
  const std::uint32_t material = materialOf(prim, path);

  readTexcoordsAndColors(prim, path, base, vertexCount, material, mesh);

  const std::vector<std::uint32_t> indices = readIndices(prim, path, vertexCount);

  const int list = materials_.materials[material].alphaTested() ? 1 : 0;
  std::size_t degenerate = 0, firstDegenerate = 0;
  auto emit = [&](std::size_t k, std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    const Eigen::Vector3f& p0 = positions[a];
    // Exactly zero area (or NaN): Embree would never report such a triangle, shading could not
    // interpolate on it, and a bake loses nothing without it.
    if (!((positions[b] - p0).cross(positions[c] - p0).squaredNorm() > 0.0f)) {
      if (degenerate++ == 0) firstDegenerate = k;
      return;
    }
    lists.triangles[list].emplace_back(int(base + a), int(base + b), int(base + c));
    lists.materials[list].push_back(material);
  };
  const std::size_t n = indices.size();
  if (prim.mode == TINYGLTF_MODE_TRIANGLES) {
    for (std::size_t i = 0; i + 2 < n; i += 3) emit(i / 3, indices[i], indices[i + 1], indices[i + 2]);
  } else if (prim.mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
    // Every other triangle of a strip is listed clockwise; the spec's order restores it.
    for (std::size_t i = 0; i + 2 < n; ++i)
      if (i % 2 == 0) emit(i, indices[i], indices[i + 1], indices[i + 2]);
      else emit(i, indices[i + 1], indices[i], indices[i + 2]);
  } else {
    for (std::size_t i = 1; i + 1 < n; ++i) emit(i - 1, indices[0], indices[i], indices[i + 1]);
  }
  degenerate_.note(degenerate, fmt::format("{} (triangle {})", path, firstDegenerate));
}

void GltfMeshReader::readTexcoordsAndColors(const tinygltf::Primitive& prim, const std::string& path, std::size_t base,
                                            std::size_t vertexCount, std::uint32_t material, Mesh& mesh) {
  // Attributes stay empty until a primitive has them; the vertices of primitives without them
  // then get the default (uv (0, 0), white), the rest are filled in by read().
  for (int set : materials_.texcoordSets) {
    int components = 0;
    const std::vector<float> uv = readAttribute(prim, fmt::format("TEXCOORD_{}", set), vertexCount, path, 2, 2,
                                                &components);
    std::vector<Eigen::Vector2f>& out = mesh.texcoords[set];
    if (uv.empty()) {
      if (!out.empty()) out.resize(base + vertexCount, Eigen::Vector2f::Zero());
      if (readsSet(materials_.materials[material], set))
        missingTexcoords_.note(1, fmt::format("{}.attributes.TEXCOORD_{}", path, set));
      continue;
    }
    out.resize(base, Eigen::Vector2f::Zero());
    for (std::size_t v = 0; v < vertexCount; ++v) out.emplace_back(uv[2 * v], uv[2 * v + 1]);
  }
  int colorComponents = 0;
  const std::vector<float> color = readAttribute(prim, "COLOR_0", vertexCount, path, 3, 4, &colorComponents);
  if (color.empty()) {
    if (!mesh.colors.empty()) mesh.colors.resize(base + vertexCount, Eigen::Vector4f::Ones());
  } else {
    mesh.colors.resize(base, Eigen::Vector4f::Ones());
    std::size_t sanitized = 0, firstSanitized = 0;
    for (std::size_t v = 0; v < vertexCount; ++v) {
      const float* c = &color[v * colorComponents];
      Eigen::Vector4f rgba(c[0], c[1], c[2], colorComponents == 4 ? c[3] : 1.0f);
      if (sanitizeColor(rgba) && sanitized++ == 0) firstSanitized = v;
      mesh.colors.push_back(rgba);
    }
    outOfRangeColors_.note(sanitized, fmt::format("{}.attributes.COLOR_0[{}]", path, firstSanitized));
  }
}

std::vector<std::uint32_t> GltfMeshReader::readIndices(const tinygltf::Primitive& prim, const std::string& path,
                                                       std::size_t vertexCount) {
  std::vector<std::uint32_t> indices;
  if (prim.indices >= 0) {
    indices = GltfAccessor(model_, prim.indices, file_, path + ".indices").readIndices();
    for (std::size_t i = 0; i < indices.size(); ++i)
      if (indices[i] >= vertexCount)
        throw InputError(fmt::format("{}: {}.indices[{}] = {} is not below the vertex count {}", file_, path, i,
                                     indices[i], vertexCount));
  } else {
    indices.resize(vertexCount);
    for (std::size_t i = 0; i < indices.size(); ++i) indices[i] = std::uint32_t(i);
  }
  return indices;
}

std::vector<Eigen::Vector3f> GltfMeshReader::readPositions(const tinygltf::Primitive& prim, const std::string& path,
                                                           const MeshPose& pose) {
  const GltfAccessor accessor(model_, prim.attributes.at("POSITION"), file_, path + ".attributes.POSITION");
  if (accessor.components() != 3) throw InputError(fmt::format("{}: {}.attributes.POSITION must be VEC3", file_, path));
  const std::vector<float> xyz = accessor.readFloats();
  const std::size_t n = accessor.count();
  std::vector<Eigen::Vector3d> p(n);
  for (std::size_t v = 0; v < n; ++v) {
    p[v] = Eigen::Vector3d(xyz[3 * v], xyz[3 * v + 1], xyz[3 * v + 2]);
    if (!p[v].allFinite())
      throw InputError(fmt::format("{}: {}.attributes.POSITION[{}] is not finite", file_, path, v));
  }
  for (std::size_t t = 0; t < prim.targets.size(); ++t) {
    const double weight = t < pose.morphWeights.size() ? pose.morphWeights[t] : 0.0;
    const auto target = prim.targets[t].find("POSITION");
    if (weight == 0.0 || target == prim.targets[t].end()) continue;
    const std::string where = fmt::format("{}.targets[{}].POSITION", path, t);
    const GltfAccessor delta(model_, target->second, file_, where);
    if (delta.components() != 3 || delta.count() != n)
      throw InputError(fmt::format("{}: {} must be VEC3 with {} elements like POSITION", file_, where, n));
    const std::vector<float> d = delta.readFloats();
    for (std::size_t v = 0; v < n; ++v) p[v] += weight * Eigen::Vector3d(d[3 * v], d[3 * v + 1], d[3 * v + 2]);
  }
  if (!pose.jointMatrices.empty()) skin(p, prim, path, pose);
  std::vector<Eigen::Vector3f> out(n);
  for (std::size_t v = 0; v < n; ++v) {
    out[v] = p[v].cast<float>();
    if (!out[v].allFinite())
      throw InputError(fmt::format("{}: {}.attributes.POSITION[{}] is not finite once morphed and skinned", file_, path,
                                   v));
  }
  return out;
}

void GltfMeshReader::skin(std::vector<Eigen::Vector3d>& positions, const tinygltf::Primitive& prim,
                          const std::string& path, const MeshPose& pose) {
  const std::size_t n = positions.size();
  std::vector<Eigen::Matrix4d> blend(n, Eigen::Matrix4d::Zero());
  std::vector<double> total(n, 0.0);
  for (int set = 0;; ++set) {
    int jc = 0, wc = 0;
    const std::vector<float> joints = readAttribute(prim, fmt::format("JOINTS_{}", set), n, path, 4, 4, &jc);
    const std::vector<float> weights = readAttribute(prim, fmt::format("WEIGHTS_{}", set), n, path, 4, 4, &wc);
    if (joints.empty() != weights.empty())
      throw InputError(fmt::format("{}: {}.attributes has only one of JOINTS_{} and WEIGHTS_{}", file_, path, set, set));
    if (joints.empty()) {
      if (set == 0)
        throw InputError(fmt::format("{}: {}.attributes has no JOINTS_0 and WEIGHTS_0, which a skinned mesh needs",
                                     file_, path));
      break;
    }
    for (std::size_t v = 0; v < n; ++v)
      for (int k = 0; k < 4; ++k) {
        const double w = weights[4 * v + k];
        if (w == 0.0) continue;
        const std::size_t joint = std::size_t(joints[4 * v + k]);
        if (joint >= pose.jointMatrices.size())
          throw InputError(fmt::format("{}: {}.attributes.JOINTS_{}[{}] = {} is not below the skin's {} joints", file_,
                                       path, set, v, joint, pose.jointMatrices.size()));
        blend[v] += w * pose.jointMatrices[joint];
        total[v] += w;
      }
  }
  // Weights should sum to 1; dividing by their sum keeps a slightly off set from scaling the
  // vertex. A vertex no joint moves stays where the file puts it.
  for (std::size_t v = 0; v < n; ++v)
    if (total[v] > 0.0) positions[v] = (blend[v] / total[v] * positions[v].homogeneous()).template head<3>();
}

std::vector<float> GltfMeshReader::readAttribute(const tinygltf::Primitive& prim, const std::string& name,
                                                 std::size_t vertices, const std::string& path, int minComponents,
                                                 int maxComponents, int* components) {
  const auto it = prim.attributes.find(name);
  if (it == prim.attributes.end()) return {};
  const std::string where = path + ".attributes." + name;
  const GltfAccessor accessor(model_, it->second, file_, where);
  if (accessor.components() < minComponents || accessor.components() > maxComponents)
    throw InputError(fmt::format("{}: {} has {} components per element, expected {}", file_, where,
                                 accessor.components(),
                                 minComponents == maxComponents ? fmt::format("{}", minComponents)
                                                                : fmt::format("{} to {}", minComponents, maxComponents)));
  if (accessor.count() != vertices)
    throw InputError(fmt::format("{}: {} has {} elements but POSITION has {}", file_, where, accessor.count(), vertices));
  *components = accessor.components();
  return accessor.readFloats();
}

std::uint32_t GltfMeshReader::materialOf(const tinygltf::Primitive& prim, const std::string& path) const {
  if (prim.material < 0) return materials_.defaultMaterial;
  if (std::size_t(prim.material) >= model_.materials.size())
    throw InputError(fmt::format("{}: {}.material refers to material {}, which does not exist", file_, path,
                                 prim.material));
  return std::uint32_t(prim.material);
}

std::vector<std::string> GltfMeshReader::warnings() const {
  std::vector<std::string> out;
  if (points_.count)
    out.push_back(fmt::format("{}: skipped {} primitive(s) of points (first: {}); points have no surface", file_,
                              points_.count, points_.first));
  if (lines_.count)
    out.push_back(fmt::format("{}: skipped {} primitive(s) of lines (first: {}); lines have no surface", file_,
                              lines_.count, lines_.first));
  if (degenerate_.count)
    out.push_back(fmt::format("{}: skipped {} degenerate triangle(s) of zero area (first: {})", file_,
                              degenerate_.count, degenerate_.first));
  if (outOfRangeColors_.count)
    out.push_back(fmt::format("{}: {} COLOR_0 colour(s) had components outside [0, 1] or not a number (first: {}); "
                              "clamped to [0, 1], NaN read as 1",
                              file_, outOfRangeColors_.count, outOfRangeColors_.first));
  if (missingTexcoords_.count)
    out.push_back(fmt::format("{}: {} primitive(s) lack a texture coordinate set their material reads (first: {}); "
                              "the texture is read at (0, 0) there",
                              file_, missingTexcoords_.count, missingTexcoords_.first));
  return out;
}

}  // namespace baker
