#include "cli/RenderCommand.h"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>

#include "cli/BakeOptions.h"
#include "cli/CommandLine.h"
#include "cli/ProgressBar.h"
#include "common/Error.h"
#include "formats/AtomicFile.h"
#include "formats/VolumeReader.h"
#include "validate/SurfaceView.h"

namespace baker {
namespace {

// Probe ids above any grid's (a grid holds far fewer than 2^39 probes) and, with the pixels
// (at most 2^22), below 2^40, where ProbeBaker puts its lattice index: the points' rays are no
// grid probe's.
constexpr std::uint64_t kFirstPointId = std::uint64_t(1) << 39;

SurfaceCamera parseCamera(const std::string& eye, const std::string& lookAt, double fov, const std::string& size) {
  SurfaceCamera camera;
  camera.eye = parseTriple("--eye", eye);
  camera.target = parseTriple("--look-at", lookAt);
  if ((camera.target - camera.eye).norm() <= 1e-9 * std::max(1.0, camera.eye.norm()))
    throw InputError("--look-at: the camera looks at its own --eye; give a point it can look towards");
  if (!std::isfinite(fov) || fov < 1.0 || fov > 170.0)
    throw InputError(fmt::format("--fov {}: expected a vertical field of view from 1 to 170 degrees", fov));
  camera.verticalFovDegrees = fov;
  char x = 0;
  std::istringstream in(size);
  if (!(in >> camera.width >> x >> camera.height) || x != 'x' || !in.eof() || camera.width < 8 || camera.height < 8 ||
      camera.width > 2048 || camera.height > 2048)
    throw InputError(fmt::format("--size {}: expected WIDTHxHEIGHT, each from 8 to 2048 pixels", size));
  return camera;
}

nlohmann::json errorJson(const SurfaceError& e) {
  return {{"mean_error_of_level", e.meanError}, {"p95_error_of_level", e.p95Error},
          {"dark_blotch_share", e.darkBlotches}, {"leak_share", e.leaks},
          {"seam_share", e.seams},              {"largest_step_of_level", e.largestStep},
          {"plane_pixel_pairs", e.planePairs}};
}

std::string errorLine(const std::string& name, const SurfaceError& e) {
  return fmt::format("{}: mean error {:.1f} % of the level (95th percentile {:.1f} %); too dark by half on {:.2f} % of lit "
                     "pixels, too bright by a quarter of the level on {:.2f} %; seams (steps over 2 % of the level "
                     "standing out from their neighbours): {:.3f} % of {} pixel pairs (largest {:.1f} %)\n",
                     name, 100 * e.meanError, 100 * e.p95Error, 100 * e.darkBlotches, 100 * e.leaks, 100 * e.seams,
                     e.planePairs, 100 * e.largestStep);
}

// The reference's estimate has no basis and no grid: the bake options that only shape a volume
// (basis, signal, window, sign constraint, distance maps, spacing) are set so that none can
// refuse it. A quality preset would trace each pixel to its own error target, far too slow for a
// picture: without --rays or --quality, 256 rays a pixel.
std::unique_ptr<BakeJob> referenceJob(const CLI::App& app, const BakeOptions& options) {
  BakeRequest request = bakeRequest(app, options);
  const BakeRequest plain;
  request.basis = plain.basis;
  request.signal = plain.signal;
  request.window = plain.window;
  request.nonNegative = false;
  request.sgSharpness.reset();
  request.hemisphereAxis.reset();
  request.distanceMap = 0;
  request.spacing.reset();  // the probe grid the job lays out is not used
  if (app.count("--rays") == 0 && app.count("--quality") == 0) request.quality.clear();
  return std::make_unique<BakeJob>(std::move(request));
}

struct Rendering {
  std::vector<SeenPoint> points;
  std::vector<std::vector<Eigen::Vector3f>> panels;  // traced, then trilinear and leak-aware
  std::int64_t seen = 0;
  double tracedLevel = 0.0, tracedSeconds = 0.0;
};

Rendering renderPanels(const BakeJob& job, const SurfaceCamera& camera, const AdaptiveVolume* levels,
                       const std::string& volumePath, bool progress) {
  Rendering r;
  const auto start = std::chrono::steady_clock::now();
  r.points = surfacesSeen(job.tracer(), camera);
  for (const SeenPoint& p : r.points) r.seen += p.seen;
  if (r.seen == 0) return r;
  {
    ProgressBar bar("tracing", progress);
    r.panels.push_back(
        tracedIrradiance(job, r.points, kFirstPointId, [&](std::int64_t d, std::int64_t n) { bar.update(d, n); }));
  }
  r.tracedSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  r.tracedLevel = surfaceLevel(r.points, r.panels.front());
  if (levels) {
    r.panels.push_back(volumeIrradiance(*levels, r.points, false, volumePath));
    // Adaptive volumes hold no distance maps.
    if (levels->coarsest().distanceMomentsPerProbe() > 0 && levels->levels.size() == 1)
      r.panels.push_back(volumeIrradiance(*levels, r.points, true, volumePath));
  }
  return r;
}

const char* const kReadings[] = {"trilinear", "leak_aware"};  // the panels after the traced one

void printRendering(bool json, const std::string& out, const SurfaceCamera& camera, const Rendering& r, double level,
                    const std::string& levelFrom, double exposure,
                    const std::vector<std::pair<std::string, SurfaceError>>& errors) {
  if (json) {
    nlohmann::json j = {{"out", out},
                        {"width", camera.width},
                        {"height", camera.height},
                        {"panels", nlohmann::json::array({"traced"})},
                        {"seen_pixels", r.seen},
                        {"level", level},
                        {"level_from", levelFrom},
                        {"exposure", exposure},
                        {"traced_seconds", r.tracedSeconds},
                        {"errors", nlohmann::json::object()}};
    for (std::size_t k = 1; k < r.panels.size(); ++k) j["panels"].push_back(kReadings[k - 1]);
    for (const auto& [name, error] : errors) j["errors"][name] = errorJson(error);
    std::cout << j.dump(2) << "\n";
    return;
  }
  std::cout << fmt::format("wrote {}: {} panel(s) of {} x {}, {} pixels see a surface; level {:.4g} ({}), exposure "
                           "{:.4g}; traced in {:.1f} s\n",
                           out, r.panels.size(), camera.width, camera.height, r.seen, level, levelFrom, exposure,
                           r.tracedSeconds);
  for (const auto& [name, error] : errors) std::cout << errorLine(name, error);
}

// A volume of another scene reads nonsense beside this one's traced irradiance; its file name is
// all a volume records of its scene.
void warnOfAnotherScene(const AdaptiveVolume& levels, const std::string& volumePath, const std::string& scenePath) {
  const auto baked = levels.coarsest().settings.find("scene");
  const std::string here = std::filesystem::path(scenePath).filename().string();
  if (baked != levels.coarsest().settings.end() && baked->second != here)
    std::cerr << fmt::format("baker render: warning: {} was baked from {}, not {}\n", volumePath, baked->second, here);
}

}  // namespace

int runRenderCommand(int argc, char** argv) {
  CLI::App app{"Draw a scene's surfaces lit by their own traced irradiance and, beside it, by a volume's."};
  app.footer("Panels, left to right: the irradiance each pixel's point receives, traced there with the bake options "
             "(--rays, default 256 per pixel rather than a --quality preset; --bounces, lights as for a bake; the basis "
             "options do not apply); with --volume, the volume read trilinearly; and, when it holds distance maps, "
             "read leak-aware (docs/LEAKS.md). Colours are x/(1+x), x = exposure x E, one exposure for all panels "
             "(automatic: 1/(2 x the level)). Dark grey: no surface.");
  BakeOptions options;
  addBakeOptions(app, options);
  std::string out, volumePath, eye, lookAt, size = "320x240";
  double fov = 60.0, exposure = 0.0, givenLevel = 0.0;
  bool json = false, quiet = false;
  app.add_option("--eye", eye, "camera position x,y,z")->required();
  app.add_option("--look-at", lookAt, "a point the camera looks at, x,y,z")->required();
  app.add_option("--fov", fov, "vertical field of view in degrees")->capture_default_str();
  app.add_option("--size", size, "picture size WIDTHxHEIGHT of each panel")->capture_default_str();
  app.add_option("--volume", volumePath, "a volume of this scene to read beside the traced irradiance");
  CLI::Option* levelOption = app.add_option(
      "--level", givenLevel,
      "the irradiance errors are shares of; default: the traced median (for a room no light reaches, the "
      "trilinear reading's)");
  CLI::Option* exposureOption = app.add_option("--exposure", exposure, "multiplier on E before the tone curve");
  app.add_option("--out", out, "PNG to write")->required();
  app.add_flag("--json", json, "print what was drawn and the errors as JSON on stdout");
  app.add_flag("--quiet", quiet, "no plan and no progress bar on stderr");
  return runGuarded("baker render", app, argc, argv, [&]() {
    const SurfaceCamera camera = parseCamera(eye, lookAt, fov, size);
    if (exposureOption->count() > 0 && (!std::isfinite(exposure) || exposure <= 0.0))
      throw InputError(fmt::format("--exposure {}: expected a finite number > 0", exposure));
    if (levelOption->count() > 0 && (!std::isfinite(givenLevel) || givenLevel <= 0.0))
      throw InputError(fmt::format("--level {}: expected a finite irradiance > 0", givenLevel));
    std::optional<AdaptiveVolume> levels;
    if (!volumePath.empty()) levels = readLevels(volumePath);
    AtomicFile file(out);
    const std::unique_ptr<BakeJob> job = referenceJob(app, options);
    for (const std::string& w : job->scene().warnings) std::cerr << "baker render: warning: " << w << "\n";
    if (!quiet) printPlan(std::cerr, job->plan());
    if (levels) warnOfAnotherScene(*levels, volumePath, options.request.scenePath);
    const Rendering r = renderPanels(*job, camera, levels ? &*levels : nullptr, volumePath, !quiet);
    if (r.seen == 0)
      throw InputError(fmt::format("--eye, --look-at: the camera sees no surface of {}; turn it towards the scene",
                                   options.request.scenePath));
    const std::string levelFrom = levelOption->count() > 0 ? "given"
                                  : r.tracedLevel > 0.0 || !levels ? "traced"
                                                                   : "trilinear";
    const double level = levelFrom == "given" ? givenLevel
                         : levelFrom == "traced" ? r.tracedLevel
                                                 : surfaceLevel(r.points, r.panels[1]);
    std::vector<std::pair<std::string, SurfaceError>> errors;
    for (std::size_t k = 1; k < r.panels.size() && level > 0.0; ++k)
      errors.emplace_back(kReadings[k - 1], compareSurfaces(r.points, r.panels[k], r.panels.front(), camera.width, level));
    if (levels && level <= 0.0)
      std::cerr << "baker render: warning: every panel is black where the camera looks, so no error is measured; "
                   "give --level\n";
    const double shownExposure = exposureOption->count() > 0 ? exposure : level > 0.0 ? 0.5 / level : 1.0;
    writeSrgbPng(surfacePanels(r.points, r.panels, camera.width, camera.height, shownExposure), 1.0,
                 file.temporaryPath());
    file.commit();
    printRendering(json, out, camera, r, level, levelFrom, shownExposure, errors);
    return 0;
  });
}

}  // namespace baker
