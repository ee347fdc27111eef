#include "cli/BakeCommand.h"

#include <fmt/format.h>
#include <tbb/global_control.h>

#include <chrono>
#include <filesystem>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "bake/Baker.h"
#include "bake/BasisRegistry.h"
#include "bake/SphericalGaussianBasis.h"
#include "cli/CommandLine.h"
#include "common/Error.h"
#include "formats/AtomicFile.h"
#include "formats/VdbWriter.h"
#include "scene/GltfLoader.h"
#include "scene/RayTracer.h"
#include "scene/SceneOptions.h"

namespace baker {
namespace {

// A grid beyond this many probes is refused before anything is traced.
constexpr std::int64_t kMaxProbes = std::int64_t(1) << 27;

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

int runBakeCommand(int argc, char** argv) {
  CLI::App app{"Bake an irradiance volume for a glTF scene."};
  app.set_version_flag("--version", BAKER_VERSION);
  std::string scenePath, basisName = "sh-l2", outPath;
  double spacing = 0.0;
  int rays = 256, threads = 0;
  bool json = false;
  app.add_option("scene", scenePath, "glTF 2.0 scene (.gltf or .glb)")->required();
  app.add_option("--basis", basisName, "basis to store (see `baker bases`)")->capture_default_str();
  app.add_option("--out", outPath, "output volume (.vdb); default: the scene's name with .vdb, here");
  app.add_option("--spacing", spacing, "probe spacing in metres; default: the longest side of the scene / 16");
  app.add_option("--rays", rays, "directions traced per probe")->capture_default_str();
  app.add_option("--threads", threads, "worker threads; default: all cores (the result does not depend on it)");
  app.add_flag("--json", json, "print the summary as JSON on stdout");
  double sgSharpness = 0.0;
  ProjectionOptions projection;
  app.add_option("--sg-sharpness", sgSharpness, "lobe sharpness λ for sg-N bases; default: measured per N");
  app.add_option("--window", projection.window.hannWidth,
                 "fade SH bands out with a Hann window of this width before projecting (paper eq. 8; less "
                 "ringing around bright small sources); default: none");
  app.add_flag("--non-negative", projection.nonNegative,
               "solve for coefficients >= 0 per probe instead of the linear projection");
  SceneOptions sceneOptions;
  addSceneOptions(app, sceneOptions);

  return runGuarded("baker", app, argc, argv, [&]() {
    if (app.count("--spacing") && !(spacing > 0.0))
      throw InputError(fmt::format("--spacing must be a positive number of metres, got {}", spacing));
    if (rays <= 0 || rays > (1 << 20)) throw InputError(fmt::format("--rays must be in 1..{}, got {}", 1 << 20, rays));
    if (threads < 0) throw InputError(fmt::format("--threads must be positive, got {}", threads));
    if (outPath.empty()) outPath = std::filesystem::path(scenePath).stem().string() + ".vdb";
    if (app.count("--sg-sharpness") && sgSharpness == 0.0)
      throw InputError("--sg-sharpness must be a positive number, got 0");
    if (projection.window.hannWidth < 0)
      throw InputError(fmt::format("--window must be a band count >= 1, got {}", projection.window.hannWidth));
    const std::unique_ptr<Basis> basis = makeBasis(basisName, sgSharpness);
    requireOutputDirectory(outPath);

    std::unique_ptr<tbb::global_control> threadLimit;
    if (threads > 0)
      threadLimit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, threads);

    const auto start = std::chrono::steady_clock::now();
    Scene scene = loadGltf(scenePath, sceneOptions);
    for (const std::string& w : scene.warnings) std::cerr << "baker: warning: " << w << "\n";
    const double loadSeconds = secondsSince(start);
    auto stage = std::chrono::steady_clock::now();
    RayTracer tracer(scene);
    const double bvhSeconds = secondsSince(stage);
    const ProbeGrid grid = makeProbeGrid(scene.bounds, spacing, kMaxProbes);

    stage = std::chrono::steady_clock::now();
    BakeStats stats;
    Volume volume = bakeVolume(scene, tracer, *basis, grid, rays, &stats, projection);
    const double bakeSeconds = secondsSince(stage);
    volume.settings["rays"] = std::to_string(rays);
    volume.settings["window"] = std::to_string(projection.window.hannWidth);
    volume.settings["non_negative"] = projection.nonNegative ? "true" : "false";
    if (const auto* sg = dynamic_cast<const SphericalGaussianBasis*>(basis.get()))
      volume.settings["sg_sharpness"] = fmt::format("{}", sg->sharpness());
    volume.settings["scene"] = std::filesystem::path(scenePath).filename().string();

    stage = std::chrono::steady_clock::now();
    writeVdb(volume, *basis, outPath);
    const double writeSeconds = secondsSince(stage);
    const double totalSeconds = secondsSince(start);

    if (json) {
      nlohmann::json j = {
          {"output", outPath},
          {"basis", basis->name()},
          {"grid", {{"dims", {grid.dims.x(), grid.dims.y(), grid.dims.z()}},
                    {"origin", {grid.origin.x(), grid.origin.y(), grid.origin.z()}},
                    {"spacing", grid.spacing}}},
          {"probes", stats.probes},
          {"bricks", stats.bricks},
          {"rays_per_probe", stats.raysPerProbe},
          {"rays_traced", stats.raysTraced},
          {"gram_condition_number", stats.conditionNumber},
          {"sample_fit_sh_order", stats.shOrder},
          {"seconds", {{"load", loadSeconds}, {"bvh", bvhSeconds}, {"operators", stats.operatorSeconds},
                       {"trace_and_project", stats.traceSeconds}, {"bake", bakeSeconds}, {"write", writeSeconds},
                       {"total", totalSeconds}}},
          {"mrays_per_second", stats.traceSeconds > 0 ? stats.raysTraced / stats.traceSeconds * 1e-6 : 0.0},
      };
      std::cout << j.dump(2) << "\n";
    } else {
      std::cerr << fmt::format("baked {} probes ({} × {} × {}, spacing {:.4g} m) × {} rays in {:.2f} s ({:.1f} Mrays/s; "
                               "operators {:.2f} s)\n",
                               stats.probes, grid.dims.x(), grid.dims.y(), grid.dims.z(), grid.spacing, rays,
                               stats.traceSeconds,
                               stats.traceSeconds > 0 ? stats.raysTraced / stats.traceSeconds * 1e-6 : 0.0,
                               stats.operatorSeconds);
      std::cout << fmt::format("wrote {} ({}, {} coefficients per probe)\n", outPath, basis->name(),
                               basis->totalCoefficients());
    }
    return 0;
  });
}

}  // namespace baker
