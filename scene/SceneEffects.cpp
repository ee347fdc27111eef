#include "scene/SceneEffects.h"

#include <fmt/format.h>

namespace baker {
namespace {

std::string lightList(const SceneCensus& c) {
  std::vector<std::string> parts;
  static const char* names[3] = {"point", "spot", "directional"};
  for (int t = 0; t < 3; ++t)
    if (c.lightsByType[t] > 0) parts.push_back(fmt::format("{} {}", c.lightsByType[t], names[t]));
  return fmt::format("{}", fmt::join(parts, ", "));
}

}  // namespace

const std::vector<std::string>& effectKeys() {
  static const std::vector<std::string> keys = {"emission",     "punctual_lights", "emissive_lights", "environment",
                                                "bounces",      "alpha_filters",   "direct_punctual", "probe_validity"};
  return keys;
}

std::vector<PlannedEffect> planEffects(const Scene& scene, const SceneCensus& c) {
  std::vector<PlannedEffect> plan;
  const std::uint64_t n = c.triangles;
  plan.push_back(c.emissiveTriangles > 0
                     ? PlannedEffect{"emission", true,
                                     fmt::format("{} of {} triangles emit (emissive factor × strength > 0)",
                                                 c.emissiveTriangles, n)}
                     : PlannedEffect{"emission", false, "no triangle has an emissive material"});
  plan.push_back(!scene.lights.empty()
                     ? PlannedEffect{"punctual_lights", true,
                                     fmt::format("{} KHR_lights_punctual light(s): {}", scene.lights.size(), lightList(c))}
                     : PlannedEffect{"punctual_lights", false, "the scene has no KHR_lights_punctual lights"});
  if (c.emissiveTriangles == 0)
    plan.push_back({"emissive_lights", false, "no triangle emits"});
  else if (c.reflectiveTriangles == 0)
    plan.push_back({"emissive_lights", false, "emissive triangles exist, but no surface reflects their light"});
  else
    plan.push_back({"emissive_lights", true,
                    fmt::format("{} emissive triangle(s) light {} reflecting triangle(s)", c.emissiveTriangles,
                                c.reflectiveTriangles)});
  if (scene.environment.kind() == Environment::Kind::None)
    plan.push_back({"environment", false, "no environment map or sky was given"});
  else if (!scene.environment.emits())
    plan.push_back({"environment", false, scene.environment.describe() + " is black"});
  else
    plan.push_back({"environment", true, scene.environment.describe()});
  plan.push_back(c.reflectiveTriangles > 0
                     ? PlannedEffect{"bounces", true,
                                     fmt::format("{} of {} triangles have a non-zero base colour", c.reflectiveTriangles, n)}
                     : PlannedEffect{"bounces", false,
                                     n == 0 ? "the scene has no triangles" : "every triangle has a zero base colour"});
  plan.push_back(c.alphaTestedTriangles > 0
                     ? PlannedEffect{"alpha_filters", true,
                                     fmt::format("{} of {} triangles are MASK or BLEND", c.alphaTestedTriangles, n)}
                     : PlannedEffect{"alpha_filters", false,
                                     n == 0 ? "the scene has no triangles" : "every triangle is OPAQUE"});
  plan.push_back(!scene.lights.empty()
                     ? PlannedEffect{"direct_punctual", true, "probes receive the punctual lights' own light as exact deltas"}
                     : PlannedEffect{"direct_punctual", false, "the scene has no KHR_lights_punctual lights"});
  plan.push_back(n > 0 ? PlannedEffect{"probe_validity", true, "probes inside geometry are moved out or filled"}
                       : PlannedEffect{"probe_validity", false, "the scene has no triangles to be inside of"});
  return plan;
}

}  // namespace baker
