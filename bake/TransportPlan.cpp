#include "bake/TransportPlan.h"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

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

std::string effectKey(std::string name) {
  std::replace(name.begin(), name.end(), '-', '_');
  return name;
}

}  // namespace

void requireKnownEffects(const std::vector<std::string>& names) {
  const std::vector<std::string>& keys = effectKeys();
  for (const std::string& name : names)
    if (std::find(keys.begin(), keys.end(), effectKey(name)) == keys.end()) {
      std::vector<std::string> flags;
      for (std::string key : keys) {
        std::replace(key.begin(), key.end(), '_', '-');
        flags.push_back(key);
      }
      throw SettingError("turned_off", fmt::format("{}: not an effect; effects are {}", name, fmt::join(flags, ", ")));
    }
}

void turnOffEffects(std::vector<PlannedEffect>& plan, const std::vector<std::string>& names) {
  requireKnownEffects(names);
  for (const std::string& name : names) {
    PlannedEffect* e = find(plan, effectKey(name));
    if (!e) throw std::logic_error("effectKeys() names an effect planEffects() does not plan: " + name);
    if (e->simulated) e->reason = fmt::format("turned off on request ({})", e->reason);
    e->simulated = false;
  }
}

TransportSettings transportSettings(std::vector<PlannedEffect>& plan, int bounces, std::uint64_t seed) {
  PlannedEffect* reflections = find(plan, "bounces");
  if (reflections && reflections->simulated && bounces == 0) {
    reflections->simulated = false;
    reflections->reason = "0 bounces asked for: probes see emission and sky only";
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
