#include "bake/TransportPlan.h"

#include <fmt/format.h>

#include <algorithm>

#include "common/Error.h"

namespace baker {
namespace {

PlannedEffect* find(std::vector<PlannedEffect>& plan, const std::string& name) {
  for (PlannedEffect& e : plan)
    if (e.name == name) return &e;
  return nullptr;
}

bool simulated(std::vector<PlannedEffect>& plan, const std::string& name) {
  const PlannedEffect* e = find(plan, name);
  return e && e->simulated;
}

}  // namespace

void turnOffEffects(std::vector<PlannedEffect>& plan, const std::vector<std::string>& names) {
  for (std::string name : names) {
    const std::string given = name;
    std::replace(name.begin(), name.end(), '-', '_');
    PlannedEffect* e = find(plan, name);
    if (!e) {
      std::vector<std::string> keys;
      for (const PlannedEffect& p : plan) {
        keys.push_back(p.name);
        std::replace(keys.back().begin(), keys.back().end(), '_', '-');
      }
      throw InputError(fmt::format("--no {}: not an effect; effects are {}", given, fmt::join(keys, ", ")));
    }
    if (e->simulated) e->reason = fmt::format("turned off by --no {} ({})", given, e->reason);
    e->simulated = false;
  }
}

TransportSettings transportSettings(std::vector<PlannedEffect>& plan, int bounces, std::uint64_t seed) {
  if (bounces < 0 || bounces > 64) throw InputError(fmt::format("--bounces must be in 0..64, got {}", bounces));
  PlannedEffect* reflections = find(plan, "bounces");
  if (reflections && reflections->simulated && bounces == 0) {
    reflections->simulated = false;
    reflections->reason = "--bounces 0: probes see emission and sky only";
  } else if (reflections && reflections->simulated && !simulated(plan, "punctual_lights") &&
             !simulated(plan, "emissive_lights") && !simulated(plan, "environment")) {
    reflections->simulated = false;
    reflections->reason = fmt::format("nothing lights the surfaces in this bake ({})", reflections->reason);
  } else if (reflections && reflections->simulated) {
    reflections->reason += fmt::format("; up to {} diffuse reflection(s) per path", bounces);
  }
  if (!simulated(plan, "bounces"))
    for (const char* name : {"punctual_lights", "emissive_lights"}) {
      PlannedEffect* e = find(plan, name);
      if (e && e->simulated) {
        e->simulated = false;
        e->reason = fmt::format("no surface reflects light in this bake ({})", e->reason);
      }
    }
  TransportSettings s;
  s.emission = simulated(plan, "emission");
  s.punctualLights = simulated(plan, "punctual_lights");
  s.emissiveLights = simulated(plan, "emissive_lights");
  s.environment = simulated(plan, "environment");
  s.bounces = simulated(plan, "bounces") ? bounces : 0;
  s.alphaFilters = simulated(plan, "alpha_filters");
  s.directPunctual = simulated(plan, "direct_punctual");
  s.probeValidity = simulated(plan, "probe_validity");
  s.seed = seed;
  return s;
}

}  // namespace baker
