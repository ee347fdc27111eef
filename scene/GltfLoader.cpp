#include "scene/GltfLoader.h"

#include <fmt/format.h>
#include <tiny_gltf.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>

#include "common/Error.h"
#include "scene/GltfAccessor.h"

namespace baker {
namespace {

const std::set<std::string> kSupportedRequiredExtensions = {"KHR_materials_emissive_strength"};

// Textures are not decoded by this loader yet, so image payloads are skipped rather than
// decoded for nothing (and a broken image does not stop a bake that does not use it).
bool skipImage(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int, void*) {
  return true;
}

Eigen::Matrix4d localTransform(const tinygltf::Node& node) {
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  if (node.matrix.size() == 16) {
    for (int c = 0; c < 4; ++c)
      for (int r = 0; r < 4; ++r) m(r, c) = node.matrix[c * 4 + r];  // glTF is column-major
    return m;
  }
  Eigen::Affine3d t = Eigen::Affine3d::Identity();
  if (node.translation.size() == 3) t.translate(Eigen::Vector3d(node.translation[0], node.translation[1], node.translation[2]));
  if (node.rotation.size() == 4)
    t.rotate(Eigen::Quaterniond(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]).normalized());
  if (node.scale.size() == 3) t.scale(Eigen::Vector3d(node.scale[0], node.scale[1], node.scale[2]));
  return t.matrix();
}

class SceneBuilder {
 public:
  SceneBuilder(const tinygltf::Model& model, const std::string& file) : model_(model), file_(file) {}

  Scene build() {
    scene_.sourcePath = file_;
    loadMaterials();
    if (!model_.scenes.empty()) {
      int sceneIndex = model_.defaultScene >= 0 ? model_.defaultScene : 0;
      if (sceneIndex >= int(model_.scenes.size()))
        throw InputError(fmt::format("{}: scene {} does not exist ({} scenes)", file_, sceneIndex, model_.scenes.size()));
      for (int root : model_.scenes[sceneIndex].nodes)
        visitNode(root, Eigen::Matrix4d::Identity(), 0, fmt::format("scenes[{}].nodes", sceneIndex));
    }
    if (degenerate_ > 0)
      scene_.warnings.push_back(fmt::format("{}: skipped {} degenerate triangles", file_, degenerate_));
    scene_.bounds.setEmpty();
    for (const Eigen::Vector3i& t : scene_.triangles)
      for (int k = 0; k < 3; ++k) scene_.bounds.extend(scene_.positions[t[k]]);
    return std::move(scene_);
  }

 private:
  void loadMaterials() {
    for (std::size_t i = 0; i < model_.materials.size(); ++i) {
      const tinygltf::Material& src = model_.materials[i];
      Material m;
      m.name = src.name;
      const auto& bc = src.pbrMetallicRoughness.baseColorFactor;
      if (bc.size() >= 3) m.baseColor = Eigen::Vector3f(float(bc[0]), float(bc[1]), float(bc[2]));
      double strength = 1.0;
      auto ext = src.extensions.find("KHR_materials_emissive_strength");
      if (ext != src.extensions.end() && ext->second.Has("emissiveStrength"))
        strength = ext->second.Get("emissiveStrength").GetNumberAsDouble();
      const auto& ef = src.emissiveFactor;
      if (ef.size() >= 3) m.emission = Eigen::Vector3f(float(ef[0] * strength), float(ef[1] * strength), float(ef[2] * strength));
      m.doubleSided = src.doubleSided;
      std::string path = fmt::format("materials[{}]", i);
      if (!m.baseColor.allFinite() || !m.emission.allFinite() || m.emission.minCoeff() < 0.0f || m.baseColor.minCoeff() < 0.0f)
        throw InputError(fmt::format("{}: {}: base colour and emission must be finite and non-negative", file_, path));
      scene_.materials.push_back(m);
    }
    // Primitives without a material use the glTF default: white, not emissive, single-sided.
    defaultMaterial_ = std::uint32_t(scene_.materials.size());
    scene_.materials.push_back(Material{"(default)", {1, 1, 1}, {0, 0, 0}, false});
  }

  void visitNode(int index, const Eigen::Matrix4d& parent, int depth, const std::string& referrer) {
    if (index < 0 || index >= int(model_.nodes.size()))
      throw InputError(fmt::format("{}: {} refers to node {}, which does not exist", file_, referrer, index));
    if (depth > int(model_.nodes.size()))
      throw InputError(fmt::format("{}: nodes[{}] is its own ancestor (the node hierarchy has a cycle)", file_, index));
    const tinygltf::Node& node = model_.nodes[index];
    Eigen::Matrix4d world = parent * localTransform(node);
    if (!world.allFinite())
      throw InputError(fmt::format("{}: nodes[{}] has a transform that is not finite", file_, index));
    if (node.mesh >= 0) addMesh(node.mesh, world, index);
    for (int child : node.children) visitNode(child, world, depth + 1, fmt::format("nodes[{}].children", index));
  }

  void addMesh(int meshIndex, const Eigen::Matrix4d& world, int nodeIndex) {
    if (meshIndex >= int(model_.meshes.size()))
      throw InputError(fmt::format("{}: nodes[{}].mesh refers to mesh {}, which does not exist", file_, nodeIndex, meshIndex));
    const tinygltf::Mesh& mesh = model_.meshes[meshIndex];
    // A mirroring transform turns counter-clockwise triangles clockwise: swap two corners
    // so that front faces stay front faces.
    const bool flip = world.topLeftCorner<3, 3>().determinant() < 0.0;
    for (std::size_t p = 0; p < mesh.primitives.size(); ++p) {
      const tinygltf::Primitive& prim = mesh.primitives[p];
      std::string path = fmt::format("meshes[{}].primitives[{}]", meshIndex, p);
      if (prim.mode != TINYGLTF_MODE_TRIANGLES && prim.mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
          prim.mode != TINYGLTF_MODE_TRIANGLE_FAN) {
        if (warnedModes_.insert(prim.mode).second)
          scene_.warnings.push_back(fmt::format("{}: {}: mode {} (points or lines) has no surface and is skipped", file_,
                                                path, prim.mode));
        continue;
      }
      auto pos = prim.attributes.find("POSITION");
      if (pos == prim.attributes.end())
        throw InputError(fmt::format("{}: {}.attributes has no POSITION", file_, path));
      GltfAccessor positions(model_, pos->second, file_, path + ".attributes.POSITION");
      if (positions.components() != 3)
        throw InputError(fmt::format("{}: {}.attributes.POSITION must be VEC3", file_, path));
      std::vector<float> xyz = positions.readFloats();
      const std::size_t base = scene_.positions.size();
      for (std::size_t v = 0; v < positions.count(); ++v) {
        Eigen::Vector4d local(xyz[3 * v], xyz[3 * v + 1], xyz[3 * v + 2], 1.0);
        if (!local.allFinite())
          throw InputError(fmt::format("{}: {}.attributes.POSITION[{}] is not finite", file_, path, v));
        Eigen::Vector4d w = world * local;
        scene_.positions.push_back(Eigen::Vector3f(float(w.x()), float(w.y()), float(w.z())));
      }

      std::vector<std::uint32_t> indices;
      if (prim.indices >= 0) {
        indices = GltfAccessor(model_, prim.indices, file_, path + ".indices").readIndices();
        for (std::size_t i = 0; i < indices.size(); ++i)
          if (indices[i] >= positions.count())
            throw InputError(fmt::format("{}: {}.indices[{}] = {} is not below the vertex count {}", file_, path, i,
                                         indices[i], positions.count()));
      } else {
        indices.resize(positions.count());
        for (std::size_t i = 0; i < indices.size(); ++i) indices[i] = std::uint32_t(i);
      }

      std::uint32_t material = defaultMaterial_;
      if (prim.material >= 0) {
        if (prim.material >= int(model_.materials.size()))
          throw InputError(fmt::format("{}: {}.material refers to material {}, which does not exist", file_, path, prim.material));
        material = std::uint32_t(prim.material);
      }
      auto emit = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
        if (flip) std::swap(b, c);
        Eigen::Vector3i tri(int(base + a), int(base + b), int(base + c));
        const Eigen::Vector3f& p0 = scene_.positions[tri[0]];
        Eigen::Vector3f n = (scene_.positions[tri[1]] - p0).cross(scene_.positions[tri[2]] - p0);
        if (!(n.squaredNorm() > 0.0f)) {
          ++degenerate_;
          return;
        }
        scene_.triangles.push_back(tri);
        scene_.triangleMaterial.push_back(material);
      };
      const std::size_t n = indices.size();
      if (prim.mode == TINYGLTF_MODE_TRIANGLES) {
        for (std::size_t i = 0; i + 2 < n; i += 3) emit(indices[i], indices[i + 1], indices[i + 2]);
      } else if (prim.mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
        // Every other triangle of a strip is listed clockwise; the spec's order restores it.
        for (std::size_t i = 0; i + 2 < n; ++i)
          if (i % 2 == 0) emit(indices[i], indices[i + 1], indices[i + 2]);
          else emit(indices[i + 1], indices[i], indices[i + 2]);
      } else {
        for (std::size_t i = 1; i + 1 < n; ++i) emit(indices[0], indices[i], indices[i + 1]);
      }
    }
  }

  const tinygltf::Model& model_;
  std::string file_;
  Scene scene_;
  std::uint32_t defaultMaterial_ = 0;
  std::size_t degenerate_ = 0;
  std::set<int> warnedModes_;
};

}  // namespace

Scene loadGltf(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw InputError(fmt::format("{}: scene file does not exist or is not a regular file", path));
  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(skipImage, nullptr);
  tinygltf::Model model;
  std::string err, warn;
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  bool ok = ext == ".glb" ? loader.LoadBinaryFromFile(&model, &err, &warn, path)
                          : loader.LoadASCIIFromFile(&model, &err, &warn, path);
  if (!ok) {
    std::string reason = err.empty() ? "not a valid glTF 2.0 file" : err;
    while (!reason.empty() && (reason.back() == '\n' || reason.back() == ' ')) reason.pop_back();
    std::replace(reason.begin(), reason.end(), '\n', ';');
    throw InputError(fmt::format("{}: cannot load glTF: {}", path, reason));
  }
  for (const std::string& required : model.extensionsRequired)
    if (!kSupportedRequiredExtensions.count(required))
      throw InputError(fmt::format("{}: extensionsRequired names {}, which this baker does not support", path, required));
  Scene scene = SceneBuilder(model, path).build();
  return scene;
}

}  // namespace baker
