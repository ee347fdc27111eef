#include "cli/BakeCommand.h"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "bake/Baker.h"
#include "bake/ProbeBaker.h"
#include "bake/SphericalGaussianBasis.h"
#include "cli/BakeOptions.h"
#include "cli/CommandLine.h"
#include "cli/ProgressBar.h"
#include "common/Timing.h"
#include "formats/VolumeMetadata.h"
#include "formats/VolumeWriter.h"
#include "images/ImageFiles.h"

namespace baker {
namespace {


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
                 "output volume: a .vdb file, or a directory of EXR slices; default: the scene's name with .vdb "
                 "(or _exr), here");
  app.add_option("--format", format, "vdb or exr; default: from --out (.vdb: vdb, else exr), vdb without --out");
  app.add_option("--precision", precision, "EXR slices: half or float")->capture_default_str();
  app.add_flag("--json", json, "print the summary as JSON on stdout");

  return runGuarded("baker", app, argc, argv, [&]() {
    const VolumeOutput output = volumeOutput(options.scenePath, outPath, format, precision);
    // EXR slices are written through the image module: a missing one fails now, not after the bake.
    if (output.format == VolumeFormat::Exr) requireImageModule();
    const auto start = std::chrono::steady_clock::now();
    std::ostringstream silenced;
    PreparedBake prepared = prepareBake(app, options, quiet ? silenced : std::cerr);
    const Basis& basis = *prepared.basis;
    const ProbeGrid& grid = prepared.grid;

    auto stage = std::chrono::steady_clock::now();
    BakeStats stats;
    Volume volume;
    {
      ProgressBar bar("baking", !quiet);
      volume = bakeVolume(*prepared.scene, *prepared.tracer, basis, grid, prepared.settings, &stats,
                          [&](std::int64_t done, std::int64_t total) { bar.update(done, total); });
    }
    const double bakeSeconds = secondsSince(stage);
    const ConvergenceSettings& convergence = prepared.settings.convergence;
    volume.settings["rays"] = std::to_string(prepared.settings.rays);
    volume.settings["quality"] = qualityName(options, prepared.settings);
    if (convergence.adaptive()) {
      volume.settings["target_error"] = fmt::format("{}", convergence.targetError);
      volume.settings["min_rays"] = std::to_string(raysAfterRounds(prepared.settings.rays, convergence.minRounds));
      volume.settings["max_rays"] = std::to_string(raysAfterRounds(prepared.settings.rays, convergence.maxRounds));
    }
    volume.settings["bounces"] = std::to_string(prepared.settings.transport.bounces);
    volume.settings["seed"] = std::to_string(options.seed);
    volume.settings["sampler"] = ProbeBaker::samplerName(prepared.settings);
    for (const PlannedEffect& e : prepared.plan) volume.settings["effect." + e.name] = e.simulated ? "on" : "off";
    volume.settings["window"] = std::to_string(options.projection.window.hannWidth);
    volume.settings["non_negative"] = options.projection.nonNegative ? "true" : "false";
    if (const auto* sg = dynamic_cast<const SphericalGaussianBasis*>(&basis))
      volume.settings["sg_sharpness"] = fmt::format("{}", sg->sharpness());
    volume.settings["scene"] = std::filesystem::path(options.scenePath).filename().string();
    volume.settings["scene_fnv1a64"] = fileHash(options.scenePath);

    stage = std::chrono::steady_clock::now();
    writeVolume(volume, basis, output);
    const double writeSeconds = secondsSince(stage);
    const double totalSeconds = secondsSince(start);
    const double mrays = stats.traceSeconds > 0 ? stats.rays.total() / stats.traceSeconds * 1e-6 : 0.0;
    const RoundTally& lattice = stats.lattice;
    const double meanRays = lattice.probes > 0 ? double(lattice.rays) / double(lattice.probes) : 0.0;
    const std::int64_t limitRays = raysAfterRounds(prepared.settings.rays, convergence.maxRounds);

    if (json) {
      nlohmann::json j = {
          {"output", output.path},
          {"format", output.format == VolumeFormat::Vdb ? "vdb" : "exr"},
          {"basis", basis.name()},
          {"grid", {{"dims", {grid.dims.x(), grid.dims.y(), grid.dims.z()}},
                    {"origin", {grid.origin.x(), grid.origin.y(), grid.origin.z()}},
                    {"spacing", grid.spacing}}},
          {"probes", stats.probes},
          {"probe_states", {{"valid", stats.validProbes}, {"relocated", stats.relocatedProbes},
                            {"invalid", stats.invalidProbes}}},
          {"bricks", stats.bricks},
          {"rays_per_probe", std::llround(meanRays)},
          {"sampling", {{"quality", volume.settings["quality"]},
                        {"target_relative_error", convergence.targetError},
                        {"mean_rays_per_probe", meanRays},
                        {"most_rays_per_probe", lattice.mostRays},
                        {"ray_limit", convergence.adaptive() ? limitRays : std::int64_t(stats.raysPerProbe)},
                        {"probes_at_ray_limit", lattice.atLimit}}},
          {"bounces", prepared.settings.transport.bounces},
          {"seed", options.seed},
          {"plan", planJson(prepared.plan)},
          {"rays", rayCountsJson(stats.rays)},
          {"rays_traced", stats.rays.total()},
          {"gram_condition_number", stats.conditionNumber},
          {"sample_fit_sh_order", stats.shOrder},
          {"seconds", {{"load", prepared.loadSeconds}, {"bvh", prepared.bvhSeconds}, {"operators", stats.operatorSeconds},
                       {"trace_and_project", stats.traceSeconds}, {"bake", bakeSeconds}, {"write", writeSeconds},
                       {"total", totalSeconds}}},
          {"mrays_per_second", mrays},
          {"peak_memory_bytes", peakMemoryBytes()},
      };
      std::cout << j.dump(2) << "\n";
    } else {
      const RayCounts& r = stats.rays;
      const std::string raysText =
          convergence.adaptive()
              ? fmt::format("{:.0f} rays on average (quality {}: to {} % standard error, {} probes stopped at "
                            "the limit of {} rays, the most any probe traced: {})",
                            meanRays, options.quality, 100.0 * convergence.targetError, lattice.atLimit,
                            limitRays, lattice.mostRays)
              : std::to_string(stats.raysPerProbe);
      std::cerr << fmt::format(
          "baked {} probes ({} × {} × {}, spacing {:.4g} m; {} relocated, {} invalid and filled) × {} rays, {} "
          "bounce(s), in {:.2f} s ({:.1f} Mrays/s; operators {:.2f} s; load {:.2f} s, BVH {:.2f} s, write {:.2f} "
          "s; peak memory {:.0f} MiB)\n"
          "rays: {} probe, {} bounce, {} punctual shadow, {} emitter shadow, {} environment shadow, {} direct "
          "punctual shadow, {} direct view, {} direct-view shadow, {} aimed bounce, {} aimed-bounce shadow, {} validity; {} in all\n",
          stats.probes, grid.dims.x(), grid.dims.y(), grid.dims.z(), grid.spacing, stats.relocatedProbes,
          stats.invalidProbes, raysText, prepared.settings.transport.bounces, stats.traceSeconds, mrays,
          stats.operatorSeconds, prepared.loadSeconds, prepared.bvhSeconds, writeSeconds,
          peakMemoryBytes() / 1048576.0, r.probe, r.bounce, r.punctualShadow, r.emitterShadow, r.environmentShadow,
          r.directPunctualShadow, r.directView, r.directViewShadow, r.aimedBounce, r.aimedBounceShadow, r.validity, r.total());
      std::cout << fmt::format("wrote {} ({}, {} coefficients per probe)\n", output.path, basis.name(),
                               basis.totalCoefficients());
    }
    return 0;
  });
}

}  // namespace baker
