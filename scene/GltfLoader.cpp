#include "scene/GltfLoader.h"

#include <fmt/format.h>
#include <tiny_gltf.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>

#include "common/Error.h"
#include "scene/GltfAccessor.h"
#include "scene/GltfFiles.h"
#include "scene/GltfImages.h"
#include "scene/GltfLights.h"
#include "scene/GltfMaterials.h"
#include "scene/GltfMeshReader.h"
#include "scene/GltfReferences.h"

namespace baker {
namespace {

// Extensions this loader applies; a file may require these and no others.
const std::set<std::string> kAppliedExtensions = {"KHR_materials_emissive_strength", "KHR_mesh_quantization",
                                                  "KHR_texture_transform", "KHR_lights_punctual"};

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

// Counts one kind of thing the loader assumed, remembering the first node for the message.
struct Tally {
  std::size_t count = 0;
  int firstNode = -1;
  void note(int node) {
    if (count++ == 0) firstNode = node;
  }
};

class SceneBuilder {
 public:
  SceneBuilder(const tinygltf::Model& model, const std::string& file, const GltfImages& images, int requestedScene)
      : model_(model), file_(file), images_(images), requestedScene_(requestedScene) {}

  Scene build() {
    scene_.sourcePath = file_;
    linkParents();
    GltfMaterials materials = readMaterials(model_, images_, file_, scene_.warnings);
    GltfMeshReader reader(model_, file_, materials);
    selectScene();
    if (scene_.sceneIndex >= 0) {
      visitScene();
      readProbeHints();
    }
    for (int node : meshNodes_) instantiate(node, reader);
    for (const std::string& w : reader.warnings()) scene_.warnings.push_back(w);
    reportAssumptions();
    scene_.materials = std::move(materials.materials);
    scene_.images = std::move(materials.images);
    computeBounds();
    scene_.extensionsUsed = model_.extensionsUsed;
    for (const std::string& e : model_.extensionsUsed)
      if (!kAppliedExtensions.count(e)) scene_.extensionsIgnored.push_back(e);
    if (!scene_.extensionsIgnored.empty())
      scene_.warnings.push_back(fmt::format("{}: not applied (no effect on a diffuse bake, or not supported): {}", file_,
                                            fmt::join(scene_.extensionsIgnored, ", ")));
    return std::move(scene_);
  }

 private:
  [[noreturn]] void fail(const std::string& what) const { throw InputError(fmt::format("{}: {}", file_, what)); }

  // glTF's node hierarchy is a set of disjoint trees: every child exists and has one parent.
  void linkParents() {
    parent_.assign(model_.nodes.size(), -1);
    for (std::size_t n = 0; n < model_.nodes.size(); ++n)
      for (int child : model_.nodes[n].children) {
        if (child < 0 || std::size_t(child) >= model_.nodes.size())
          fail(fmt::format("nodes[{}].children refers to node {}, which does not exist", n, child));
        if (parent_[child] >= 0)
          fail(fmt::format("nodes[{}] is a child of both nodes[{}] and nodes[{}]; glTF nodes have one parent", child,
                           parent_[child], n));
        parent_[child] = int(n);
      }
    world_.resize(model_.nodes.size());
    known_.assign(model_.nodes.size(), false);
  }

  // The node's world transform, its ancestors' transforms applied; computed once.
  const Eigen::Matrix4d& world(int node) {
    std::vector<int> chain;
    int n = node;
    while (n >= 0 && !known_[n]) {
      chain.push_back(n);
      if (chain.size() > model_.nodes.size())
        fail(fmt::format("nodes[{}] is its own ancestor (the node hierarchy has a cycle)", node));
      n = parent_[n];
    }
    Eigen::Matrix4d m = n >= 0 ? world_[n] : Eigen::Matrix4d::Identity();
    for (auto it = chain.rbegin(); it != chain.rend(); ++it) {
      m = m * localTransform(model_.nodes[*it]);
      if (!m.allFinite()) fail(fmt::format("nodes[{}] has a transform that is not finite", *it));
      world_[*it] = m;
      known_[*it] = true;
    }
    return world_[node];
  }

  void selectScene() {
    const int count = int(model_.scenes.size());
    scene_.sceneCount = count;
    if (requestedScene_ >= 0) {
      if (requestedScene_ >= count)
        throw SettingError("scene", fmt::format("{}: {}: the file has {} scene(s)", requestedScene_, file_, count));
      scene_.sceneIndex = requestedScene_;
    } else if (count == 0) {
      if (!model_.nodes.empty())
        scene_.warnings.push_back(fmt::format("{}: the file defines no scenes, so none of its {} nodes is loaded", file_,
                                              model_.nodes.size()));
    } else {
      scene_.sceneIndex = model_.defaultScene >= 0 ? model_.defaultScene : 0;
      if (scene_.sceneIndex >= count)
        fail(fmt::format("scene {} does not exist ({} scenes)", scene_.sceneIndex, count));
    }
  }

  void readProbeHints() {
    const tinygltf::Value& extras = model_.scenes[scene_.sceneIndex].extras;
    if (!extras.IsObject() || !extras.Has("probe_hint")) return;
    const tinygltf::Value& hints = extras.Get("probe_hint");
    const std::string where = fmt::format("scenes[{}].extras.probe_hint", scene_.sceneIndex);
    // extras are the author's own data: a hint this reader cannot use is skipped, never a reason
    // to refuse a scene every other command loads.
    if (!hints.IsArray()) {
      scene_.warnings.push_back(where + " is not an array of [x, y, z] positions: ignored");
      return;
    }
    for (std::size_t h = 0; h < hints.ArrayLen(); ++h) {
      const tinygltf::Value& hint = hints.Get(int(h));
      Eigen::Vector3f position;
      bool valid = hint.IsArray() && hint.ArrayLen() == 3;
      for (int a = 0; valid && a < 3; ++a) {
        valid = hint.Get(a).IsNumber();
        if (valid) position[a] = float(hint.Get(a).GetNumberAsDouble());
      }
      if (valid && position.allFinite())
        scene_.probeHints.push_back(position);
      else
        scene_.warnings.push_back(fmt::format("{}[{}] is not a finite [x, y, z] position: ignored", where, h));
    }
  }

  // Depth first from the scene's roots, without recursion: hierarchies can be deep.
  void visitScene() {
    std::vector<bool> seen(model_.nodes.size(), false);
    std::vector<int> stack;
    const tinygltf::Scene& s = model_.scenes[scene_.sceneIndex];
    for (auto it = s.nodes.rbegin(); it != s.nodes.rend(); ++it) {
      if (*it < 0 || std::size_t(*it) >= model_.nodes.size())
        fail(fmt::format("scenes[{}].nodes refers to node {}, which does not exist", scene_.sceneIndex, *it));
      stack.push_back(*it);
    }
    while (!stack.empty()) {
      const int n = stack.back();
      stack.pop_back();
      if (seen[n])
        fail(fmt::format("nodes[{}] is reached twice from scenes[{}] (listed twice, or the hierarchy has a cycle)", n,
                         scene_.sceneIndex));
      seen[n] = true;
      const tinygltf::Node& node = model_.nodes[n];
      if (node.mesh >= 0) {
        if (std::size_t(node.mesh) >= model_.meshes.size())
          fail(fmt::format("nodes[{}].mesh refers to mesh {}, which does not exist", n, node.mesh));
        meshNodes_.push_back(n);
      }
      if (std::optional<PunctualLight> light = readLight(model_, n, world(n), file_))
        scene_.lights.push_back(std::move(*light));
      for (auto it = node.children.rbegin(); it != node.children.rend(); ++it) stack.push_back(*it);
    }
  }

  std::vector<double> morphWeights(const tinygltf::Node& node, int nodeIndex) const {
    const bool fromNode = !node.weights.empty();
    const std::vector<double>& w = fromNode ? node.weights : model_.meshes[node.mesh].weights;
    for (double x : w)
      if (!std::isfinite(x))
        fail(fromNode ? fmt::format("nodes[{}].weights has a value that is not finite", nodeIndex)
                      : fmt::format("meshes[{}].weights has a value that is not finite", node.mesh));
    return w;
  }

  // world(joint) × inverseBindMatrix for every joint of the node's skin: the joints where their
  // nodes stand, so the skinned mesh takes its rest pose in world space.
  std::vector<Eigen::Matrix4d> jointMatrices(int nodeIndex) {
    const int skinIndex = model_.nodes[nodeIndex].skin;
    if (std::size_t(skinIndex) >= model_.skins.size())
      fail(fmt::format("nodes[{}].skin refers to skin {}, which does not exist", nodeIndex, skinIndex));
    const tinygltf::Skin& skin = model_.skins[skinIndex];
    const std::string path = fmt::format("skins[{}]", skinIndex);
    std::vector<float> inverseBind;
    if (skin.inverseBindMatrices >= 0) {
      const GltfAccessor ibm(model_, skin.inverseBindMatrices, file_, path + ".inverseBindMatrices");
      if (ibm.components() != 16 || ibm.count() < skin.joints.size())
        fail(fmt::format("{}.inverseBindMatrices must be {} MAT4 elements", path, skin.joints.size()));
      inverseBind = ibm.readFloats();
    }
    std::vector<Eigen::Matrix4d> joints;
    for (std::size_t j = 0; j < skin.joints.size(); ++j) {
      const int joint = skin.joints[j];
      if (joint < 0 || std::size_t(joint) >= model_.nodes.size())
        fail(fmt::format("{}.joints[{}] refers to node {}, which does not exist", path, j, joint));
      Eigen::Matrix4d bind = Eigen::Matrix4d::Identity();
      if (!inverseBind.empty()) bind = Eigen::Map<const Eigen::Matrix4f>(&inverseBind[16 * j]).cast<double>();
      joints.push_back(world(joint) * bind);
    }
    return joints;
  }

  void instantiate(int nodeIndex, GltfMeshReader& reader) {
    const tinygltf::Node& node = model_.nodes[nodeIndex];
    const tinygltf::Mesh& mesh = model_.meshes[node.mesh];
    const bool hasTargets = std::any_of(mesh.primitives.begin(), mesh.primitives.end(),
                                        [](const tinygltf::Primitive& p) { return !p.targets.empty(); });
    const bool skinned = node.skin >= 0;
    MeshPose pose;
    if (hasTargets) {
      pose.morphWeights = morphWeights(node, nodeIndex);
      morphed_.note(nodeIndex);
    }
    Instance instance;
    instance.node = nodeIndex;
    if (skinned) {
      // A skinned mesh is posed in world space by its joints; glTF ignores its node's transform.
      pose.jointMatrices = jointMatrices(nodeIndex);
      skinned_.note(nodeIndex);
    } else {
      const Eigen::Matrix4d& w = world(nodeIndex);
      const Eigen::Matrix3d linear = w.topLeftCorner<3, 3>();
      if (!(std::abs(linear.determinant()) > 0.0)) {
        singular_.note(nodeIndex);
        return;
      }
      instance.objectToWorld = w.cast<float>();
      instance.normalToWorld = linear.inverse().transpose().cast<float>();
      if (!instance.objectToWorld.allFinite() || !instance.normalToWorld.allFinite())
        fail(fmt::format("nodes[{}] has a transform beyond floating-point range", nodeIndex));
    }
    // A mesh posed for this node alone (skinned, or morphed with the node's own weights) is read
    // for it; any other use of a mesh shares one copy.
    const bool ownPose = skinned || (hasTargets && !node.weights.empty());
    const auto shared = sharedMeshes_.find(node.mesh);
    if (!ownPose && shared != sharedMeshes_.end()) {
      instance.mesh = shared->second;
    } else {
      instance.mesh = std::uint32_t(scene_.meshes.size());
      scene_.meshes.push_back(reader.read(node.mesh, pose));
      if (!ownPose) sharedMeshes_.emplace(node.mesh, instance.mesh);
    }
    instance.firstTriangle = nextTriangle_;
    nextTriangle_ += scene_.meshes[instance.mesh].triangleCount();
    scene_.instances.push_back(instance);
  }

  void reportAssumptions() {
    std::vector<std::string> parts;
    if (skinned_.count)
      parts.push_back(fmt::format("{} skinned mesh instance(s) (first: nodes[{}]) in their rest pose, with the joints "
                                  "where their nodes stand",
                                  skinned_.count, skinned_.firstNode));
    if (morphed_.count)
      parts.push_back(fmt::format("{} mesh instance(s) with morph targets (first: nodes[{}]) at their default weights",
                                  morphed_.count, morphed_.firstNode));
    if (!model_.animations.empty())
      parts.push_back(fmt::format("{} animation(s) not applied", model_.animations.size()));
    if (!parts.empty())
      scene_.warnings.push_back(fmt::format("{}: baked in the default pose: {}", file_, fmt::join(parts, "; ")));
    if (singular_.count)
      scene_.warnings.push_back(fmt::format("{}: skipped {} mesh instance(s) whose node transform is singular (first: "
                                            "nodes[{}]); they have no area",
                                            file_, singular_.count, singular_.firstNode));
  }

  // Bounds of the vertices triangles use, placed by every instance.
  void computeBounds() {
    scene_.bounds.setEmpty();
    std::vector<std::vector<bool>> used(scene_.meshes.size());
    for (const Instance& instance : scene_.instances) {
      const Mesh& mesh = scene_.meshes[instance.mesh];
      std::vector<bool>& u = used[instance.mesh];
      if (u.empty()) {
        u.assign(mesh.positions.size(), false);
        for (const Eigen::Vector3i& t : mesh.triangles) u[t[0]] = u[t[1]] = u[t[2]] = true;
      }
      const Eigen::Matrix3f linear = instance.objectToWorld.topLeftCorner<3, 3>();
      const Eigen::Vector3f offset = instance.objectToWorld.topRightCorner<3, 1>();
      for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
        if (!u[v]) continue;
        const Eigen::Vector3f p = linear * mesh.positions[v] + offset;
        if (!p.allFinite())
          fail(fmt::format("nodes[{}] places {} vertex {} beyond floating-point range", instance.node, mesh.source, v));
        scene_.bounds.extend(p);
      }
    }
  }

  const tinygltf::Model& model_;
  const std::string& file_;
  const GltfImages& images_;
  int requestedScene_;
  Scene scene_;
  std::vector<int> parent_;
  std::vector<Eigen::Matrix4d> world_;
  std::vector<bool> known_;
  std::vector<int> meshNodes_;
  std::map<int, std::uint32_t> sharedMeshes_;
  std::uint64_t nextTriangle_ = 0;
  Tally skinned_, morphed_, singular_;
};

}  // namespace

Scene loadGltf(const std::string& path, const SceneOptions& options) {
  // The environment first: a bad flag should not wait for a large scene to load.
  std::vector<std::string> environmentWarnings;
  Environment environment = environmentFromOptions(options, environmentWarnings);

  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw InputError(fmt::format("{}: scene file does not exist or is not a regular file", path));
  const nlohmann::json json = readGltfJson(path);
  checkExternalUris(json, path);
  checkReferencesTinygltfRejects(json, path);
  tinygltf::TinyGLTF loader;
  GltfImages images;
  images.install(loader);
  const std::string folder = sceneFolderOf(path);
  loader.SetFsCallbacks(confinedFileSystem(folder));
  tinygltf::Model model;
  std::string err, warn;
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  const bool ok = ext == ".glb" ? loader.LoadBinaryFromFile(&model, &err, &warn, path)
                                : loader.LoadASCIIFromFile(&model, &err, &warn, path);
  if (!ok) throw InputError(fmt::format("{}: cannot load glTF: {}", path, err.empty() ? "not a valid glTF 2.0 file" : oneLine(err)));
  for (const std::string& required : model.extensionsRequired)
    if (!kAppliedExtensions.count(required))
      throw InputError(fmt::format("{}: extensionsRequired names {}, which this baker does not support", path, required));

  Scene scene = SceneBuilder(model, path, images, options.scene).build();
  scene.environment = std::move(environment);
  scene.warnings.insert(scene.warnings.end(), environmentWarnings.begin(), environmentWarnings.end());
  return scene;
}

}  // namespace baker
