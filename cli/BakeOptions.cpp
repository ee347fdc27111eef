#include "cli/BakeOptions.h"

#include <fmt/format.h>

#include <ostream>

#include "bake/ProbeConvergence.h"
#include "cli/CommandLine.h"
#include "cli/SceneFlags.h"
#include "common/Error.h"
#include "volume/MemoryEstimate.h"

namespace baker {

void addBakeOptions(CLI::App& app, BakeOptions& o, bool listed) {
  BakeRequest& r = o.request;
  if (listed) r.quality.clear();  // lists of ray counts: each a fixed bake
  app.add_option("scene", r.scenePath, "glTF 2.0 scene (.gltf or .glb)")->required();
  app.add_option("--spacing", o.spacing, "probe spacing in metres; default: the longest side of the scene / 16, at most 1 m");
  if (!listed) {
    app.add_option("--basis", r.basis, "basis to store (see `baker bases`)")->capture_default_str();
    auto* quality = app.add_option("--quality", r.quality,
                                   qualityPresetNames() +
                                       ": each probe traces lattices that double in size until the standard error "
                                       "of its irradiance is small enough (docs/SAMPLING.md)")
                        ->capture_default_str();
    app.add_option("--rays", r.rays, "a fixed number of directions per probe, one path each, in place of --quality")
        ->excludes(quality);
    app.add_option("--share-reflections", r.sharedReflectionCell,
                   "SIZE in metres: with --rays, the probes of a brick share what their paths bring back from "
                   "surfaces, averaged over cells of SIZE (less noise for a bias of the light's variation across a "
                   "cell; docs/SAMPLING.md); 0: none");
    app.add_option("--bounces", r.bounces,
                   "diffuse reflections per path: 0 = emission and sky seen directly, 1 = adds the direct lighting "
                   "of the first surface hit")
        ->capture_default_str();
  }
  app.add_option("--seed", r.seed, "random seed; the same seed gives bit-identical volumes at any thread count")
      ->capture_default_str();
  app.add_option("--no", r.turnedOff,
                 "turn an effect off (repeatable): emission, punctual-lights, emissive-lights, environment, bounces, "
                 "alpha-filters, direct-punctual, probe-validity")
      ->allow_extra_args(false);
  app.add_option("--threads", r.threads, "worker threads; default: all cores (the result does not depend on it)");
  app.add_option("--sg-sharpness", o.sgSharpness, "lobe sharpness λ for sg-N bases; default: measured per N");
  app.add_option("--hemisphere-axis", o.hemisphereAxis,
                 "x,y,z: the axis ad-hemi9's hemisphere is about, e.g. a wall's normal; default 0,1,0 (up)");
  app.add_option("--window", r.window.hannWidth,
                 "fade SH bands out with a Hann window of this width before projecting (paper eq. 8; less "
                 "ringing around bright small sources); default: none");
  app.add_flag("--non-negative", r.nonNegative,
               "solve for coefficients >= 0 per probe instead of the linear projection");
  app.add_option("--distance-map", o.distanceMap,
                 "texels per side of each probe's octahedral map of distances to the nearest surfaces and of the "
                 "sky's share, which `baker sample --leak-aware` reads to keep light from leaking through walls and "
                 "`baker relight` to see the sky; 0: none (relight then reads the visibility coefficients); default "
                 "8 with uniform placement (adaptive volumes hold none)");
  app.add_option("--signal", r.signal,
                 "what the coefficients hold: irradiance (E(n), one lookup per normal) or radiance (L(ω), whose "
                 "irradiance `baker sample` reconstructs from each function's diffuse response)")
      ->capture_default_str();
  addSceneFlags(app, r.scene);
}

void addPlacementOptions(CLI::App& app, BakeRequest& request) {
  app.add_option("--placement", request.placement,
                 "uniform: one grid at --spacing; adaptive: --levels nested levels, the finest at --spacing, "
                 "finer bricks only near geometry (docs/ADAPTIVE.md); written as .vdb or EXR slices")
      ->capture_default_str();
  app.add_option("--levels", request.levels, "adaptive placement: 1 to 4 levels, spacing ×3 per level")
      ->capture_default_str();
  app.add_option("--margin", request.marginCells,
                 "adaptive placement: a brick is refined when geometry lies within it or this many of its cells "
                 "around it (1 to 4)")
      ->capture_default_str();
}

void requirePlacementOptions(const CLI::App& app, const BakeRequest& request) {
  for (const char* flag : {"--levels", "--margin"})
    if (app.count(flag) && !request.adaptive()) throw SettingError(flag + 2, "applies to --placement adaptive only");
}

BakeRequest bakeRequest(const CLI::App& app, const BakeOptions& options) {
  BakeRequest request = options.request;
  if (app.count("--spacing")) request.spacing = options.spacing;
  if (app.count("--sg-sharpness")) request.sgSharpness = options.sgSharpness;
  if (app.count("--distance-map")) request.distanceMap = options.distanceMap;
  if (app.count("--hemisphere-axis")) request.hemisphereAxis = parseTriple("--hemisphere-axis", options.hemisphereAxis);
  if (app.count("--rays")) request.quality.clear();
  return request;
}

std::unique_ptr<BakeJob> prepareBake(const CLI::App& app, const BakeOptions& options, std::ostream& log) {
  auto job = std::make_unique<BakeJob>(bakeRequest(app, options));
  for (const std::string& w : job->scene().warnings) log << "baker: warning: " << w << "\n";
  const ProbeGrid& g = job->grid();
  const int shards = job->request().shard ? job->request().shard->count : 1;
  log << fmt::format("grid: {} × {} × {} = {} probes, spacing {:.4g} m ({}), {:.3g} GiB at the peak{}\n", g.dims.x(),
                     g.dims.y(), g.dims.z(), g.probeCount(), g.spacing, job->spacingReason(),
                     bakeMemoryBytes(g, shards, job->basis(), job->settings().distanceValuesPerProbe()) / double(1ull << 30),
                     shards > 1 ? " per shard (the merge, or rank 0 under MPI, holds the whole volume)" : "");
  if (job->placement()) printPlacement(log, *job);
  printPlan(log, job->plan());
  return job;
}

double uniformFinestProbes(const BakeJob& job) {
  const AdaptivePlacement* placement = job.placement();
  return probesPerAxis(job.scene().bounds, placement ? placement->grids.back().spacing : job.grid().spacing).prod();
}

void printPlacement(std::ostream& log, const BakeJob& job) {
  const AdaptivePlacement& p = *job.placement();
  log << fmt::format("adaptive placement: {} levels, spacing ×{} per level, probes traced within {} cell(s) of "
                     "geometry\n",
                     p.levels(), kLevelRatio, p.marginCells);
  for (int level = 0; level < p.levels(); ++level) {
    const ProbeGrid& g = p.grids[std::size_t(level)];
    log << fmt::format("  level {}: spacing {:.4g} m, {} of {} bricks, {} probes{}\n", level, g.spacing,
                       p.bricks[std::size_t(level)].size(), g.brickCount(), p.probes(level),
                       level == 0 && p.deepInsideBricks > 0
                           ? fmt::format(" ({} bricks deep inside closed geometry not placed)", p.deepInsideBricks)
                           : "");
  }
  const double uniform = uniformFinestProbes(job);
  log << fmt::format("  in all {} probes, {:.3g} GiB at the peak; a uniform grid at {:.4g} m would have {:.4g} probes "
                     "({:.3g}× as many)\n",
                     p.probes(), volumeMemoryBytes(double(p.probes()), job.basis()) / double(1ull << 30),
                     p.grids.back().spacing, uniform, uniform / double(std::max<std::int64_t>(1, p.probes())));
}

void printPlan(std::ostream& out, const std::vector<PlannedEffect>& plan) {
  out << "plan:\n";
  for (const PlannedEffect& e : plan)
    out << fmt::format("  {:<16} {:<3}  {}\n", e.name, e.simulated ? "on" : "off", e.reason);
}

void printExportPlan(std::ostream& log, const VolumeOutput& output, const Basis& basis, StoredSignal signal,
                     bool nonNegativeForFormat) {
  if (const std::string conversion = volumeConversion(output, basis, signal); !conversion.empty())
    log << fmt::format("export for {}: {}{}\n", volumeFormatName(output.format), conversion,
                       nonNegativeForFormat ? "; the fit is solved for coefficients >= 0, which the format's texels hold"
                                            : "");
}

Shard requireShard(const std::string& text) {
  const std::optional<Shard> shard = parseShard(text);
  if (!shard) throw SettingError("shard", fmt::format("{}: expected K/N, whole numbers with 0 <= K < N <= {}", text, kMaxShards));
  return *shard;
}

nlohmann::json planJson(const std::vector<PlannedEffect>& plan) {
  nlohmann::json j = nlohmann::json::object();
  for (const PlannedEffect& e : plan) j[e.name] = {{"simulated", e.simulated}, {"reason", e.reason}};
  return j;
}

nlohmann::json rayCountsJson(const RayCounts& r) {
  return {{"probe", r.probe},
          {"bounce", r.bounce},
          {"punctual_shadow", r.punctualShadow},
          {"emitter_shadow", r.emitterShadow},
          {"environment_shadow", r.environmentShadow},
          {"direct_punctual_shadow", r.directPunctualShadow},
          {"direct_view", r.directView},
          {"direct_view_shadow", r.directViewShadow},
          {"aimed_bounce", r.aimedBounce},
          {"aimed_bounce_shadow", r.aimedBounceShadow},
          {"validity", r.validity},
          {"total", r.total()}};
}

}  // namespace baker
