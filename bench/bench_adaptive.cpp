// Adaptive placement against a uniform grid at its finest spacing: probes, file bytes, bake time,
// and the irradiance error added at points near surfaces.
//
//   bench_adaptive SCENE.gltf --spacing S [--levels L] [--margin M] [--rays R] [--bounces B]
//                  [--reference-rays R] [--points N] [--out DIR] [--json]
//
// Three bakes: uniform at S and adaptive with finest spacing S, both with R rays and seed 0, and a
// reference: uniform at S with the reference's rays (default 16 R, a quarter of the noise) and
// seed 1, so that its noise is its own. Each is written as .vdb to DIR. E(n) (mean of R, G, B) is
// sampled, as an engine samples it, at N points on the scene's surfaces (triangles drawn by area
// with a fixed seed, a tenth of S off the front side, n the front normal), from the volume as
// baked. An adaptive volume is its file (the bake keeps only the bricks the file keeps); a uniform
// file leaves out bricks, reading as zeros, only where every corner of a cell lies inside geometry
// (volume/StoredBricks.h), which the points on the scene's outermost faces can reach and an
// engine never shows. A volume's error is the
// RMS of its difference from the reference over the points, relative to the reference's mean; the
// error adaptive placement adds is its error minus the uniform bake's. Also reported: how far the
// adaptive volume lies from the uniform bake itself (whose finest-level probes draw the same random
// streams, so that this is the change adaptive placement makes, plus the uniform bake's noise where
// it does).
#include <fmt/format.h>

#include <chrono>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>
#include <random>
#include <string>
#include <vector>

#include "bake/BakeJob.h"
#include "cli/CommandLine.h"
#include "common/PeakMemory.h"
#include "formats/VolumeWriter.h"

namespace baker {
namespace {

struct PointNearSurface {
  Eigen::Vector3d position, normal;
};

void worldCorners(const Instance& instance, const Mesh& mesh, std::uint32_t triangle, Eigen::Vector3d (&corners)[3]) {
  for (int k = 0; k < 3; ++k)
    corners[k] = (instance.objectToWorld.cast<double>() *
                  mesh.positions[std::size_t(mesh.triangles[triangle][k])].cast<double>().homogeneous())
                     .head<3>();
}

// `count` points on the scene's triangles, drawn by area, `lift` off their front side.
std::vector<PointNearSurface> surfacePoints(const Scene& scene, int count, double lift) {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> triangles;
  std::vector<double> areas;
  for (std::uint32_t i = 0; i < scene.instances.size(); ++i) {
    const Instance& instance = scene.instances[i];
    const Mesh& mesh = scene.meshes[instance.mesh];
    for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t) {
      Eigen::Vector3d c[3];
      worldCorners(instance, mesh, t, c);
      triangles.emplace_back(i, t);
      areas.push_back(0.5 * (c[1] - c[0]).cross(c[2] - c[0]).norm());
    }
  }
  std::mt19937_64 random(20261204);
  std::discrete_distribution<std::size_t> pick(areas.begin(), areas.end());
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<PointNearSurface> points;
  while (int(points.size()) < count && !triangles.empty()) {
    const auto [i, t] = triangles[pick(random)];
    const Instance& instance = scene.instances[i];
    const Mesh& mesh = scene.meshes[instance.mesh];
    double u = unit(random), v = unit(random);
    if (u + v > 1.0) u = 1.0 - u, v = 1.0 - v;
    Eigen::Vector3d c[3];
    worldCorners(instance, mesh, t, c);
    const Eigen::Vector3d normal = scene.frontNormal(i, t).cast<double>();
    if (!normal.allFinite() || normal.norm() < 0.5) continue;
    points.push_back({c[0] + u * (c[1] - c[0]) + v * (c[2] - c[0]) + lift * normal, normal});
  }
  return points;
}

struct Bake {
  AdaptiveVolume volume;
  BakeStats stats;
  double seconds = 0.0;
  std::uintmax_t bytes = 0;
  std::vector<double> irradiance;  // at the points
};

Bake bake(BakeRequest request, const std::string& path, const std::vector<PointNearSurface>& points) {
  Bake b;
  const BakeJob job(std::move(request));
  const auto start = std::chrono::steady_clock::now();
  b.volume = job.bakeLevels(&b.stats);
  b.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  VolumeOutput output;
  output.path = path;
  writeLevels(b.volume, job.basis(), output);
  b.bytes = std::filesystem::file_size(path);
  std::vector<float> coefficients(std::size_t(b.volume.coarsest().coefficientsPerProbe));
  std::vector<float> visibility(std::size_t(b.volume.coarsest().visibilityPerProbe));
  for (const PointNearSurface& p : points) {
    sampleLevels(b.volume.levels, int(b.volume.levels.size()), p.position, coefficients.data(), visibility.data());
    b.irradiance.push_back(double(job.basis().reconstruct(coefficients.data(), p.normal).mean()));
  }
  b.volume = {};  // three volumes of a large scene need not be held at once
  return b;
}

// RMS of (a − reference) over the points, relative to the reference's mean.
double relativeRmse(const std::vector<double>& a, const std::vector<double>& reference) {
  double squares = 0.0, mean = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    squares += (a[i] - reference[i]) * (a[i] - reference[i]);
    mean += reference[i];
  }
  return std::sqrt(squares / double(a.size())) / (mean / double(a.size()));
}

nlohmann::json bakeJson(const Bake& b, const std::vector<double>& reference) {
  return {{"probes", b.stats.probes},
          {"bytes", b.bytes},
          {"bake_seconds", b.seconds},
          {"rays", b.stats.rays.total()},
          {"relative_rmse_against_reference", relativeRmse(b.irradiance, reference)}};
}

}  // namespace
}  // namespace baker

int main(int argc, char** argv) {
  using namespace baker;
  CLI::App app{"Adaptive placement against a uniform grid at its finest spacing."};
  BakeRequest request;
  double spacing = 0.0;
  int points = 4000, referenceRays = 0;
  std::string out = ".";
  bool json = false;
  app.add_option("scene", request.scenePath, "glTF scene")->required();
  app.add_option("--spacing", spacing, "the finest spacing, and the uniform grid's")->required();
  app.add_option("--levels", request.levels, "levels of the adaptive bake")->capture_default_str();
  app.add_option("--margin", request.marginCells, "margin of the adaptive bake, in cells")->capture_default_str();
  app.add_option("--rays", request.rays, "rays per probe (fixed)")->capture_default_str();
  app.add_option("--bounces", request.bounces, "bounces")->capture_default_str();
  app.add_option("--reference-rays", referenceRays, "rays per probe of the reference; default 16 × --rays");
  app.add_option("--points", points, "points near surfaces")->capture_default_str();
  app.add_option("--out", out, "folder for the three volumes")->capture_default_str();
  app.add_flag("--json", json, "JSON on stdout");
  return runGuarded("bench_adaptive", app, argc, argv, [&]() {
    request.spacing = spacing;
    request.quality.clear();
    std::filesystem::create_directories(out);
    const Scene scene = BakeJob(request).scene();  // a copy, for the points
    const std::vector<PointNearSurface> surface = surfacePoints(scene, points, 0.1 * spacing);
    BakeRequest referenceRequest = request;
    referenceRequest.seed = 1;
    referenceRequest.rays = referenceRays > 0 ? referenceRays : 16 * request.rays;
    const Bake reference = bake(referenceRequest, out + "/reference.vdb", surface);
    const Bake uniform = bake(request, out + "/uniform.vdb", surface);
    BakeRequest adaptive = request;
    adaptive.placement = "adaptive";
    const Bake levels = bake(adaptive, out + "/adaptive.vdb", surface);
    const double floor = relativeRmse(uniform.irradiance, reference.irradiance);
    const double error = relativeRmse(levels.irradiance, reference.irradiance);
    const nlohmann::json report = {
        {"scene", std::filesystem::path(request.scenePath).filename().string()},
        {"spacing", spacing},
        {"levels", request.levels},
        {"margin_cells", request.marginCells},
        {"rays", request.rays},
        {"bounces", request.bounces},
        {"points", surface.size()},
        {"reference_rays", referenceRequest.rays},
        {"reference", bakeJson(reference, reference.irradiance)},
        {"uniform", bakeJson(uniform, reference.irradiance)},
        {"adaptive", bakeJson(levels, reference.irradiance)},
        {"adaptive_against_uniform", relativeRmse(levels.irradiance, uniform.irradiance)},
        {"probe_ratio", double(uniform.stats.probes) / double(levels.stats.probes)},
        {"byte_ratio", double(uniform.bytes) / double(levels.bytes)},
        {"rmse_added", error - floor},
        {"peak_memory_bytes", peakMemoryBytes()}};
    if (json)
      std::cout << report.dump(2) << "\n";
    else
      std::cout << fmt::format("{}: uniform {} probes, {} bytes; adaptive {} probes, {} bytes ({:.2f}× fewer probes, {:.2f}× "
                               "fewer bytes); near-surface RMSE against the reference: uniform {:.2f} %, adaptive {:.2f} %, "
                               "added {:.2f} %; adaptive against uniform {:.2f} %\n",
                               report["scene"].get<std::string>(), uniform.stats.probes, uniform.bytes,
                               levels.stats.probes, levels.bytes, report["probe_ratio"].get<double>(),
                               report["byte_ratio"].get<double>(), 100 * floor, 100 * error, 100 * (error - floor),
                               100 * report["adaptive_against_uniform"].get<double>());
    return 0;
  });
}
