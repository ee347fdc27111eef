#include "cli/InfoCommand.h"

#include <fmt/format.h>

#include <iostream>
#include <nlohmann/json.hpp>

#include "cli/CommandLine.h"
#include "cli/SceneFlags.h"
#include "scene/GltfLoader.h"
#include "scene/SceneCensus.h"
#include "scene/SceneEffects.h"

namespace baker {
namespace {

const char* kindName(Environment::Kind kind) {
  switch (kind) {
    case Environment::Kind::None: return "none";
    case Environment::Kind::Constant: return "constant";
    case Environment::Kind::Map: break;
  }
  return "map";
}

nlohmann::json vector3(const Eigen::Vector3f& v) { return {v.x(), v.y(), v.z()}; }

nlohmann::json environmentJson(const Environment& env) {
  nlohmann::json j = {{"kind", kindName(env.kind())}, {"emits", env.emits()}};
  if (env.kind() == Environment::Kind::Constant) j["radiance"] = vector3(env.constantRadiance());
  if (env.kind() == Environment::Kind::Map) {
    j["file"] = env.source();
    j["width"] = env.width();
    j["height"] = env.height();
    j["intensity"] = env.intensity();
    j["rotation_degrees"] = env.rotationDegrees();
    j["sanitized_texels"] = env.sanitizedTexels();
  }
  return j;
}

nlohmann::json infoJson(const Scene& scene, const SceneCensus& c, const std::vector<PlannedEffect>& plan) {
  nlohmann::json effects = nlohmann::json::object();
  for (const PlannedEffect& e : plan) effects[e.name] = {{"simulated", e.simulated}, {"reason", e.reason}};
  return {
      {"file", scene.sourcePath},
      {"scene", scene.sceneIndex},
      {"scene_count", scene.sceneCount},
      {"geometry",
       {{"triangles", c.triangles},
        {"unique_triangles", c.uniqueTriangles},
        {"meshes", scene.meshes.size()},
        {"instances", scene.instances.size()},
        {"instanced_meshes", c.instancedMeshes}}},
      {"bounds", scene.bounds.isEmpty()
                     ? nlohmann::json(nullptr)
                     : nlohmann::json{{"min", vector3(scene.bounds.min())}, {"max", vector3(scene.bounds.max())}}},
      {"materials",
       {{"defined", scene.materials.size() - 1},
        {"in_use", c.materialsInUse},
        {"by_alpha_mode",
         {{"opaque", c.materialsByAlphaMode[0]}, {"mask", c.materialsByAlphaMode[1]}, {"blend", c.materialsByAlphaMode[2]}}},
        {"double_sided", c.doubleSidedMaterials},
        {"textured", c.texturedMaterials}}},
      {"lights",
       {{"total", scene.lights.size()},
        {"point", c.lightsByType[0]},
        {"spot", c.lightsByType[1]},
        {"directional", c.lightsByType[2]}}},
      {"textures", {{"decoded", scene.images.size()}, {"texels", c.textureTexels}, {"bytes", c.textureBytes}}},
      {"extensions", {{"used", scene.extensionsUsed}, {"ignored", scene.extensionsIgnored}}},
      {"environment", environmentJson(scene.environment)},
      {"effects", effects},
      {"warnings", scene.warnings},
  };
}

void printText(const Scene& scene, const SceneCensus& c, const std::vector<PlannedEffect>& plan) {
  std::cout << fmt::format("{} (scene {} of {})\n", scene.sourcePath, scene.sceneIndex, scene.sceneCount);
  std::cout << fmt::format("geometry: {} triangles ({} unique), {} meshes, {} instances ({} meshes instanced)\n",
                           c.triangles, c.uniqueTriangles, scene.meshes.size(), scene.instances.size(),
                           c.instancedMeshes);
  if (scene.bounds.isEmpty()) {
    std::cout << "bounds: empty\n";
  } else {
    const Eigen::Vector3f lo = scene.bounds.min(), hi = scene.bounds.max();
    std::cout << fmt::format("bounds: ({:.4g}, {:.4g}, {:.4g}) to ({:.4g}, {:.4g}, {:.4g})\n", lo.x(), lo.y(), lo.z(),
                             hi.x(), hi.y(), hi.z());
  }
  std::cout << fmt::format("materials: {} (opaque {}, mask {}, blend {}), {} double-sided, {} textured, {} in use\n",
                           scene.materials.size() - 1, c.materialsByAlphaMode[0], c.materialsByAlphaMode[1],
                           c.materialsByAlphaMode[2], c.doubleSidedMaterials, c.texturedMaterials, c.materialsInUse);
  std::cout << fmt::format("lights: {} (point {}, spot {}, directional {})\n", scene.lights.size(), c.lightsByType[0],
                           c.lightsByType[1], c.lightsByType[2]);
  std::cout << fmt::format("textures: {} decoded, {} texels, {:.1f} MiB\n", scene.images.size(), c.textureTexels,
                           c.textureBytes / 1048576.0);
  std::cout << fmt::format("extensions: used [{}], ignored [{}]\n", fmt::join(scene.extensionsUsed, ", "),
                           fmt::join(scene.extensionsIgnored, ", "));
  std::cout << fmt::format("environment: {}{}\n", scene.environment.describe(),
                           scene.environment.sanitizedTexels() > 0
                               ? fmt::format(", {} texels sanitised to 0", scene.environment.sanitizedTexels())
                               : "");
  std::cout << "effects a bake would simulate:\n";
  for (const PlannedEffect& e : plan)
    std::cout << fmt::format("  {:<16} {:<4} {}\n", e.name, e.simulated ? "on" : "off", e.reason);
}

}  // namespace

int runInfoCommand(int argc, char** argv) {
  CLI::App app{"Describe what baker loads from a glTF scene and which effects a bake would simulate."};
  std::string scenePath;
  bool json = false;
  app.add_option("scene", scenePath, "glTF 2.0 scene (.gltf or .glb)")->required();
  app.add_flag("--json", json, "print the description as JSON on stdout");
  SceneOptions options;
  addSceneFlags(app, options);
  return runGuarded("baker info", app, argc, argv, [&]() {
    const Scene scene = loadGltf(scenePath, options);
    const SceneCensus census = takeCensus(scene);
    const std::vector<PlannedEffect> plan = planEffects(scene, census);
    if (json) {
      std::cout << infoJson(scene, census, plan).dump(2) << "\n";
    } else {
      for (const std::string& w : scene.warnings) std::cerr << "baker info: warning: " << w << "\n";
      printText(scene, census, plan);
    }
    return 0;
  });
}

}  // namespace baker
