#pragma once
#include <CLI/CLI.hpp>

#include <iosfwd>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "bake/BakeJob.h"
#include "bake/BakeRequest.h"
#include "bake/Transport.h"
#include "formats/VolumeWriter.h"
#include "scene/SceneEffects.h"

namespace baker {

// The flags `baker SCENE` and `baker probe SCENE` share, as they fill a BakeRequest.
struct BakeOptions {
  BakeRequest request;
  double spacing = 0.0, sgSharpness = 0.0;  // taken only when their flag is given
  std::string hemisphereAxis;
  int distanceMap = DistanceMapLayout::kDefaultSize;
};

// `listed`: a command that takes lists of bases, ray and bounce counts registers its own
// --basis, --rays and --bounces.
void addBakeOptions(CLI::App& app, BakeOptions& options, bool listed = false);

// Probes a uniform grid at the bake's finest spacing would have: what adaptive placement saves.
double uniformFinestProbes(const BakeJob& job);
// An adaptive bake's levels: spacing, bricks and probes per level, against a uniform grid.
void printPlacement(std::ostream& log, const BakeJob& job);

// --placement, --levels, --margin: the bake command's own (a list of bakes or single probes has
// no levels); the last two are refused without adaptive placement.
void addPlacementOptions(CLI::App& app, BakeRequest& request);
void requirePlacementOptions(const CLI::App& app, const BakeRequest& request);

// The request the parsed flags describe.
BakeRequest bakeRequest(const CLI::App& app, const BakeOptions& options);

// Prepares the bake (BakeJob) and prints the scene's warnings and the plan to `log`.
std::unique_ptr<BakeJob> prepareBake(const CLI::App& app, const BakeOptions& options, std::ostream& log);

void printPlan(std::ostream& out, const std::vector<PlannedEffect>& plan);
// The line saying how an engine's format will hold the basis (nothing for baker's own formats).
void printExportPlan(std::ostream& log, const VolumeOutput& output, const Basis& basis, StoredSignal signal,
                     bool nonNegativeForFormat);
// The shard --shard K/N names; SettingError("shard") otherwise.
Shard requireShard(const std::string& text);
nlohmann::json planJson(const std::vector<PlannedEffect>& plan);
nlohmann::json rayCountsJson(const RayCounts& rays);

}  // namespace baker
