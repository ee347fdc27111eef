#pragma once
#include <CLI/CLI.hpp>
#include <tbb/global_control.h>

#include <cstdint>
#include <iosfwd>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "bake/Basis.h"
#include "bake/ProbeBaker.h"
#include "bake/ProbeGrid.h"
#include "scene/RayTracer.h"
#include "scene/Scene.h"
#include "scene/SceneEffects.h"
#include "scene/SceneOptions.h"

namespace baker {

// The options `baker SCENE` and `baker probe SCENE` share: what to bake and how.
struct BakeOptions {
  std::string scenePath;
  std::string basisName = "sh-l2";
  double spacing = 0.0;
  int rays = 256;
  std::string quality;  // a preset of qualityPresets(); empty: `rays` rays, fixed
  int bounces = 3;
  std::uint64_t seed = 0;
  int threads = 0;
  std::vector<std::string> turnedOff;  // --no EFFECT
  double sgSharpness = 0.0;
  ProjectionOptions projection;
  SceneOptions scene;
};

// `listed`: a command that takes lists of bases, ray and bounce counts registers its own
// --basis, --rays and --bounces.
void addBakeOptions(CLI::App& app, BakeOptions& options, bool listed = false);

// Everything a bake needs once the options are checked: the basis, the loaded scene and its
// BVH, the grid, and the effect plan with the settings it implies.
struct PreparedBake {
  std::unique_ptr<Basis> basis;
  std::unique_ptr<Scene> scene;
  std::unique_ptr<RayTracer> tracer;
  ProbeGrid grid;
  std::vector<PlannedEffect> plan;
  BakeSettings settings;
  std::unique_ptr<tbb::global_control> threadLimit;
  double loadSeconds = 0.0, bvhSeconds = 0.0;
};

// Checks the options (InputError naming the flag), loads the scene, prints its warnings and
// the plan to `log`, and builds the BVH.
PreparedBake prepareBake(const CLI::App& app, const BakeOptions& options, std::ostream& log);

// The volume's `quality` setting: the preset, or "fixed" for a --rays bake.
std::string qualityName(const BakeOptions& options, const BakeSettings& settings);

void printPlan(std::ostream& out, const std::vector<PlannedEffect>& plan);
nlohmann::json planJson(const std::vector<PlannedEffect>& plan);
nlohmann::json rayCountsJson(const RayCounts& rays);

}  // namespace baker
