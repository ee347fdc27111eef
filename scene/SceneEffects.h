#pragma once
#include <string>
#include <vector>

#include "scene/Scene.h"
#include "scene/SceneCensus.h"

namespace baker {

// One light-transport effect and whether the scene calls for it. A bake simulates only the
// effects whose `simulated` is true, and says why either way.
struct PlannedEffect {
  // Stable key: emission, punctual_lights, emissive_lights, environment, bounces, alpha_filters,
  // direct_punctual, probe_validity.
  std::string name;
  bool simulated = false;
  std::string reason;
};

// Decided from the scene alone: emission seen directly (some triangle emits), punctual lights
// (the scene has some), emissive surfaces as lights at bounce points (some triangle emits and
// some reflects), the environment (one that brings light was given), bounces (some triangle has
// a non-zero base colour), alpha filters (some triangle is MASK or BLEND), punctual lights seen
// by the probes themselves (there are some), probe validity (there is geometry to be inside of).
std::vector<PlannedEffect> planEffects(const Scene& scene, const SceneCensus& census);

// The keys of every plan, in its order.
const std::vector<std::string>& effectKeys();

}  // namespace baker
