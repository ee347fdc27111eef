#include "cli/BakeOptions.h"

#include <fmt/format.h>

#include <chrono>
#include <ostream>

#include "bake/BasisRegistry.h"
#include "bake/NonNegativeProjection.h"
#include "bake/ProbeConvergence.h"
#include "bake/TransportPlan.h"
#include "common/Error.h"
#include "common/Timing.h"
#include "scene/GltfLoader.h"
#include "scene/SceneCensus.h"

namespace baker {
namespace {

// A grid beyond this many probes is refused before anything is traced.
constexpr std::int64_t kMaxProbes = std::int64_t(1) << 27;
constexpr int kMaxRays = 1 << 20;


}  // namespace

void addBakeOptions(CLI::App& app, BakeOptions& o, bool listed) {
  app.add_option("scene", o.scenePath, "glTF 2.0 scene (.gltf or .glb)")->required();
  app.add_option("--spacing", o.spacing, "probe spacing in metres; default: the longest side of the scene / 16");
  if (!listed) {
    app.add_option("--basis", o.basisName, "basis to store (see `baker bases`)")->capture_default_str();
    o.quality = "default";
    auto* quality = app.add_option("--quality", o.quality,
                                   qualityPresetNames() +
                                       ": each probe traces lattices that double in size until the standard error "
                                       "of its irradiance is small enough (docs/SAMPLING.md)")
                        ->capture_default_str();
    app.add_option("--rays", o.rays, "a fixed number of directions per probe, one path each, in place of --quality")
        ->excludes(quality);
    app.add_option("--bounces", o.bounces,
                   "diffuse reflections per path: 0 = emission and sky seen directly, 1 = adds the direct lighting "
                   "of the first surface hit")
        ->capture_default_str();
  }
  app.add_option("--seed", o.seed, "random seed; the same seed gives bit-identical volumes at any thread count")
      ->capture_default_str();
  app.add_option("--no", o.turnedOff,
                 "turn an effect off (repeatable): emission, punctual-lights, emissive-lights, environment, bounces, "
                 "alpha-filters, direct-punctual, probe-validity")
      ->allow_extra_args(false);
  app.add_option("--threads", o.threads, "worker threads; default: all cores (the result does not depend on it)");
  app.add_option("--sg-sharpness", o.sgSharpness, "lobe sharpness λ for sg-N bases; default: measured per N");
  app.add_option("--window", o.projection.window.hannWidth,
                 "fade SH bands out with a Hann window of this width before projecting (paper eq. 8; less "
                 "ringing around bright small sources); default: none");
  app.add_flag("--non-negative", o.projection.nonNegative,
               "solve for coefficients >= 0 per probe instead of the linear projection");
  addSceneOptions(app, o.scene);
}

PreparedBake prepareBake(const CLI::App& app, const BakeOptions& o, std::ostream& log) {
  if (app.count("--spacing") && !(o.spacing > 0.0))
    throw InputError(fmt::format("--spacing must be a positive number of metres, got {}", o.spacing));
  if (o.rays <= 0 || o.rays > kMaxRays) throw InputError(fmt::format("--rays must be in 1..{}, got {}", kMaxRays, o.rays));
  if (o.threads < 0) throw InputError(fmt::format("--threads must be positive, got {}", o.threads));
  if (app.count("--sg-sharpness") && !(o.sgSharpness > 0.0))
    throw InputError(fmt::format("--sg-sharpness must be a positive number, got {}", o.sgSharpness));
  if (o.projection.window.hannWidth < 0)
    throw InputError(fmt::format("--window must be a band count >= 1, got {}", o.projection.window.hannWidth));

  PreparedBake b;
  b.basis = makeBasis(o.basisName, o.sgSharpness);
  // The constraint is on R, G and B (each in its channel's functions), or on Y; visibility uses
  // channel 0's functions.
  const int constrainedChannels = b.basis->colorSpace() == ColorSpace::Rgb ? 3 : 1;
  bool signChanging = false;
  for (int c = 0; c < constrainedChannels && o.projection.nonNegative; ++c)
    signChanging = signChanging || !functionsAreNonNegative(b.basis->functions(c));
  if (signChanging)
    throw InputError(fmt::format("--non-negative: {} functions change sign, so coefficients >= 0 do not make the "
                                 "reconstruction non-negative (and can make its ringing worse); use it with "
                                 "sh-l0, ad-linear, ad-cos2, ad-srbf, sg-* or ambient-cube",
                                 o.basisName));
  if (o.threads > 0)
    b.threadLimit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, o.threads);
  const auto start = std::chrono::steady_clock::now();
  b.scene = std::make_unique<Scene>(loadGltf(o.scenePath, o.scene));
  for (const std::string& w : b.scene->warnings) log << "baker: warning: " << w << "\n";
  b.loadSeconds = secondsSince(start);
  b.grid = makeProbeGrid(b.scene->bounds, o.spacing, kMaxProbes);

  b.plan = planEffects(*b.scene, takeCensus(*b.scene));
  turnOffEffects(b.plan, o.turnedOff);
  b.settings.rays = o.rays;
  if (!o.quality.empty() && !app.count("--rays")) {
    const QualityPreset* preset = findQualityPreset(o.quality);
    if (!preset) throw InputError(fmt::format("--quality must be one of {}, got '{}'", qualityPresetNames(), o.quality));
    b.settings.rays = preset->rays;
    b.settings.convergence = preset->convergence;
  }
  b.settings.projection = o.projection;
  b.settings.transport = transportSettings(b.plan, o.bounces, o.seed);
  printPlan(log, b.plan);

  const auto bvhStart = std::chrono::steady_clock::now();
  b.tracer = std::make_unique<RayTracer>(*b.scene, b.settings.transport.alphaFilters);
  b.bvhSeconds = secondsSince(bvhStart);
  return b;
}

std::string qualityName(const BakeOptions& options, const BakeSettings& settings) {
  return settings.convergence.adaptive() ? options.quality : "fixed";
}

void printPlan(std::ostream& out, const std::vector<PlannedEffect>& plan) {
  out << "plan:\n";
  for (const PlannedEffect& e : plan)
    out << fmt::format("  {:<16} {:<3}  {}\n", e.name, e.simulated ? "on" : "off", e.reason);
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
