#include "cli/BakeCommand.h"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "bake/BakeJob.h"
#include "bake/ProbeConvergence.h"
#include "basis/BasisRegistry.h"
#include "basis/StoredSignal.h"
#include "cli/BakeOptions.h"
#include "cli/CommandLine.h"
#include "cli/MpiBakeCommand.h"
#include "cli/ProgressBar.h"
#include "common/Timing.h"
#include "formats/VolumeWriter.h"
#include "images/ImageFiles.h"

namespace baker {
namespace {

// What one bake took, for the summary.
struct BakeReport {
  const BakeJob& job;
  const BakeStats& stats;
  VolumeOutput output;
  EngineExport engineExport;
  double bakeSeconds = 0.0, writeSeconds = 0.0, totalSeconds = 0.0;

  double meanRays() const {
    return stats.lattice.probes > 0 ? double(stats.lattice.rays) / double(stats.lattice.probes) : 0.0;
  }
  double mraysPerSecond() const {
    return stats.traceSeconds > 0 ? stats.rays.total() / stats.traceSeconds * 1e-6 : 0.0;
  }
};

nlohmann::json engineExportJson(const EngineExport& e) {
  if (e.engine.empty()) return nullptr;
  return {{"engine", e.engine},
          {"conversion", e.conversion},
          {"clamped_values", e.clampedValues},
          {"clamped_because", e.clampedBecause},
          {"warnings", e.warnings}};
}

nlohmann::json shardJson(const BakeJob& job) {
  const std::optional<Shard>& shard = job.request().shard;
  if (!shard) return nullptr;
  return {{"index", shard->index}, {"count", shard->count},
          {"bricks", job.bricksInShard()}, {"bricks_in_grid", job.bricksInBake()}};
}

nlohmann::json placementJson(const BakeJob& job) {
  nlohmann::json levels = nlohmann::json::array();
  const AdaptivePlacement* p = job.placement();
  const int count = p ? p->levels() : 1;
  for (int level = 0; level < count; ++level) {
    const ProbeGrid& g = p ? p->grids[std::size_t(level)] : job.grid();
    levels.push_back({{"level", level},
                      {"dims", {g.dims.x(), g.dims.y(), g.dims.z()}},
                      {"origin", {g.origin.x(), g.origin.y(), g.origin.z()}},
                      {"spacing", g.spacing},
                      {"bricks", p ? std::int64_t(p->bricks[std::size_t(level)].size()) : g.brickCount()},
                      {"probes", p ? p->probes(level) : g.probeCount()}});
  }
  return {{"mode", job.request().placement},
          {"margin_cells", p ? nlohmann::json(p->marginCells) : nlohmann::json(nullptr)},
          {"deep_inside_bricks", p ? p->deepInsideBricks : 0},
          {"levels", levels},
          {"uniform_finest_probes", uniformFinestProbes(job)}};
}

nlohmann::json gridJson(const BakeJob& job) {
  const ProbeGrid& grid = job.grid();
  return {{"dims", {grid.dims.x(), grid.dims.y(), grid.dims.z()}},
          {"origin", {grid.origin.x(), grid.origin.y(), grid.origin.z()}},
          {"spacing", grid.spacing},
          {"spacing_chosen", job.spacingReason()}};
}

nlohmann::json dryRunJson(const BakeJob& job) {
  return {{"basis", job.basis().name()}, {"grid", gridJson(job)}, {"placement", placementJson(job)},
          {"plan", planJson(job.plan())}};
}

nlohmann::json bakeJson(const BakeReport& r) {
  const BakeJob& job = r.job;
  const BakeStats& stats = r.stats;
  const ConvergenceSettings& convergence = job.settings().convergence;
  return {
      {"output", r.output.path},
      {"format", volumeFormatName(r.output.format)},
      {"basis", job.basis().name()},
      {"signal", storedSignalName(job.settings().projection.signal)},
      {"grid", gridJson(job)},
      {"probes", stats.probes},
      {"probe_states", {{"valid", stats.validProbes}, {"relocated", stats.relocatedProbes},
                        {"invalid", stats.invalidProbes}, {"interpolated", stats.interpolatedProbes}}},
      {"placement", placementJson(job)},
      {"bricks", stats.bricks},
      {"rays_per_probe", std::llround(r.meanRays())},
      {"sampling", {{"quality", qualityName(job.request())},
                    {"target_relative_error", convergence.targetError},
                    {"mean_rays_per_probe", r.meanRays()},
                    {"most_rays_per_probe", stats.lattice.mostRays},
                    {"ray_limit", job.rayLimit()},
                    {"probes_at_ray_limit", stats.lattice.atLimit}}},
      {"bounces", job.settings().transport.bounces},
      {"seed", job.request().seed},
      {"plan", planJson(job.plan())},
      {"rays", rayCountsJson(stats.rays)},
      {"rays_traced", stats.rays.total()},
      {"gram_condition_number", stats.conditionNumber},
      // Radiance samples are fitted in the basis itself, through no SH expansion.
      {"sample_fit_sh_order", job.settings().projection.signal == StoredSignal::Radiance ? nlohmann::json()
                                                                                        : nlohmann::json(stats.shOrder)},
      {"seconds", {{"load", job.loadSeconds()}, {"bvh", job.bvhSeconds()}, {"operators", stats.operatorSeconds},
                   {"trace_and_project", stats.traceSeconds}, {"bake", r.bakeSeconds}, {"write", r.writeSeconds},
                   {"total", r.totalSeconds}}},
      {"mrays_per_second", r.mraysPerSecond()},
      {"peak_memory_bytes", peakMemoryBytes()},
      {"engine_export", engineExportJson(r.engineExport)},
      {"shard", shardJson(job)},
  };
}

void printBakeSummary(const BakeReport& r) {
  const BakeJob& job = r.job;
  const BakeStats& stats = r.stats;
  const ProbeGrid& grid = job.grid();
  const ConvergenceSettings& convergence = job.settings().convergence;
  const RayCounts& c = stats.rays;
  const std::string raysText =
      convergence.adaptive()
          ? fmt::format("{:.0f} rays on average (quality {}: to {} % standard error, {} probes stopped at the limit "
                        "of {} rays, the most any probe traced: {})",
                        r.meanRays(), job.request().quality, 100.0 * convergence.targetError, stats.lattice.atLimit,
                        job.rayLimit(), stats.lattice.mostRays)
          : std::to_string(stats.raysPerProbe);
  std::cerr << fmt::format(
      "baked {} probes ({}; {} relocated, {} invalid{}) × {} rays, {} "
      "bounce(s), in {:.2f} s ({:.1f} Mrays/s; operators {:.2f} s; load {:.2f} s, BVH {:.2f} s, write {:.2f} "
      "s; peak memory {:.0f} MiB)\n"
      "rays: {} probe, {} bounce, {} punctual shadow, {} emitter shadow, {} environment shadow, {} direct "
      "punctual shadow, {} direct view, {} direct-view shadow, {} aimed bounce, {} aimed-bounce shadow, {} validity; "
      "{} in all\n",
      stats.probes,
      job.placement() ? fmt::format("{} levels, spacing {:.4g} to {:.4g} m, {} interpolated at level borders",
                                    job.placement()->levels(), grid.spacing, job.placement()->grids.back().spacing,
                                    stats.interpolatedProbes)
                      : fmt::format("{} × {} × {}, spacing {:.4g} m", grid.dims.x(), grid.dims.y(), grid.dims.z(), grid.spacing),
      stats.relocatedProbes,
      stats.invalidProbes, job.request().shard ? ", filled when the parts are merged" : " and filled", raysText, job.settings().transport.bounces, stats.traceSeconds, r.mraysPerSecond(),
      stats.operatorSeconds, job.loadSeconds(), job.bvhSeconds(), r.writeSeconds, peakMemoryBytes() / 1048576.0,
      c.probe, c.bounce, c.punctualShadow, c.emitterShadow, c.environmentShadow, c.directPunctualShadow, c.directView,
      c.directViewShadow, c.aimedBounce, c.aimedBounceShadow, c.validity, c.total());
  if (const std::optional<Shard>& shard = job.request().shard)
    std::cout << fmt::format("wrote {}: shard {} of the bake ({} of {} bricks, {}), to merge with the other parts "
                             "(baker merge OUT PART...)\n",
                             r.output.path, shardName(*shard), stats.bricks, job.bricksInBake(),
                             job.basis().name());
  else
    std::cout << fmt::format("wrote {} ({}, {} coefficients per probe)\n", r.output.path, job.basis().name(),
                             job.basis().totalCoefficients());
  const EngineExport& e = r.engineExport;
  if (!e.engine.empty()) std::cout << fmt::format("  for {}: {}\n", e.engine, e.conversion);
}

// A shard's part: a .vdb file or a directory of EXR slices in float, so that the merge reads back
// the very bits the bake made; named after the shard unless --out names it.
VolumeOutput partOutput(const BakeRequest& request, std::string out, const std::string& format) {
  if (format == "bevy" || format == "threejs")
    throw SettingError("format", fmt::format("{}: a shard's part is a .vdb file or an EXR directory; bake the parts "
                                             "in one of those, then `baker merge --format {} OUT PART...` writes the "
                                             "engine's files", format, format));
  if (request.adaptive() && format == "exr")
    throw SettingError("format", "exr: a shard's part of an adaptive bake is a .vdb file; `baker merge --format exr` "
                                 "writes the whole volume as EXR slices");
  if (out.empty()) {
    const Shard& s = *request.shard;
    out = fmt::format("{}_shard-{}-of-{}{}", std::filesystem::path(request.scenePath).stem().string(), s.index,
                      s.count, format == "exr" ? "_exr" : ".vdb");
  }
  const VolumeOutput output = volumeOutput(request.scenePath, out, format, "float");
  if (request.adaptive() && output.format != VolumeFormat::Vdb)
    throw SettingError("format", fmt::format("{}: a shard's part of an adaptive bake is a .vdb file; `baker merge` "
                                             "writes the whole volume as EXR slices if asked", output.path));
  return output;
}

// MPI sets the shard itself, so BakeRequest's word on one adaptive level would name --shard.
void requireSpreadOverRanks(const BakeRequest& request) {
  if (request.adaptive() && request.levels < 2)
    throw SettingError("mpi", "an adaptive bake of one level is written as a uniform volume and is not spread over "
                              "ranks; give --levels 2 or more, or bake it in one process");
}

}  // namespace

int runBakeCommand(int argc, char** argv) {
  CLI::App app{"Bake an irradiance volume for a glTF scene."};
  app.set_version_flag("--version", BAKER_VERSION);
  BakeOptions options;
  std::string outPath, format, precision = "half";
  bool json = false, quiet = false;
  addBakeOptions(app, options);
  app.add_flag("--quiet", quiet, "no plan and no progress bar on stderr (errors and warnings still)");
  app.add_option("--out", outPath,
                 "output volume: a .vdb file, or a directory (EXR slices, or an engine's files); default: the scene's "
                 "name with .vdb (or _exr, _bevy, _threejs), here");
  app.add_option("--format", format,
                 "vdb, exr, bevy (Bevy's IrradianceVolume, KTX2) or threejs (three.js's LightProbeGrid); default: "
                 "from --out (.vdb: vdb, else exr), vdb without --out");
  app.add_option("--precision", precision, "EXR slices: half or float")->capture_default_str();
  app.add_flag("--json", json, "print the summary as JSON on stdout");
  std::string shardText;
  bool mpi = false, dryRun = false;
  app.add_flag("--dry-run", dryRun,
               "lay out the grid (and an adaptive bake's levels), print the plan and stop: nothing is baked or "
               "written (adaptive placement traces its few test rays); with --json, the plan as JSON");
  auto* shardOption = app.add_option(
      "--shard", shardText,
      "bake only shard K of N (0 <= K < N <= 4096, bricks in Morton order): a part for `baker merge`; parts are "
      "written in float");
  addPlacementOptions(app, options.request);
  app.add_flag("--mpi", mpi,
               "under mpirun: rank r bakes shard r of the ranks with its share of the cores, rank 0 writes the "
               "whole volume (docs/SCALING.md)")
      ->excludes(shardOption);

  return runGuarded("baker", app, argc, argv, [&]() {
    if (!shardText.empty()) options.request.shard = requireShard(shardText);
    if (mpi) requireSpreadOverRanks(options.request);
    requirePlacementOptions(app, options.request);
    const VolumeOutput output = options.request.shard ? partOutput(options.request, outPath, format)
                                                      : volumeOutput(options.request.scenePath, outPath, format, precision);
    // EXR slices are written through the image module: a missing one fails now, not after the bake.
    if (output.format == VolumeFormat::Exr) requireImageModule();
    if (!app.count("--basis") && !preferredBasis(output).empty()) options.request.basis = preferredBasis(output);
    const std::unique_ptr<Basis> basis = makeBasis(options.request.basis);
    requireWritable(output, *basis);
    requireLevelsWritable(output, options.request.adaptive() ? options.request.levels : 1);
    const bool nonNegativeForFormat = !options.request.nonNegative && prefersNonNegativeFit(output, *basis);
    if (nonNegativeForFormat) options.request.nonNegative = true;
    if (mpi) return bakeOverMpi(app, options, output, {quiet, json, nonNegativeForFormat});
    const auto start = std::chrono::steady_clock::now();
    std::ostringstream silenced;
    const std::unique_ptr<BakeJob> job = prepareBake(app, options, quiet ? silenced : std::cerr);
    printExportPlan(quiet ? silenced : std::cerr, output, job->basis(), job->settings().projection.signal,
                    nonNegativeForFormat);
    if (dryRun) {
      if (json) std::cout << dryRunJson(*job).dump(2) << "\n";
      return 0;
    }
    BakeStats stats;
    BakeReport report{*job, stats, output, {}};
    auto stage = std::chrono::steady_clock::now();
    AdaptiveVolume volume;
    {
      ProgressBar bar("baking", !quiet);
      volume = job->bakeLevels(&stats, [&](std::int64_t done, std::int64_t total) { bar.update(done, total); });
    }
    report.bakeSeconds = secondsSince(stage);
    stage = std::chrono::steady_clock::now();
    report.engineExport = writeLevels(volume, job->basis(), output);
    for (const std::string& warning : report.engineExport.warnings)
      std::cerr << fmt::format("baker: warning: {}: {}\n", report.engineExport.engine, warning);
    if (report.engineExport.clampedValues > 0)
      std::cerr << fmt::format("baker: warning: {} values clamped for {}: {}\n", report.engineExport.clampedValues,
                               report.engineExport.engine, report.engineExport.clampedBecause);
    report.writeSeconds = secondsSince(stage);
    report.totalSeconds = secondsSince(start);
    if (json)
      std::cout << bakeJson(report).dump(2) << "\n";
    else
      printBakeSummary(report);
    return 0;
  });
}

}  // namespace baker
