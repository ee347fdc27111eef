// The bake's cost, measured as ratios within one run (these machines are noisy):
//
//   bench_bake [SCENE.gltf] [--rays N] [--basis NAME] [--spacing M] [--baker PATH] [--json]
//
// Times in 1 and 2 and in the thread scaling are each the best of five interleaved rounds, and
// the one-thread bake, its replay and its write run on one thread.
// 1. Throughput against the ray-tracing limit: bake rays per second (one thread, tracing and
//    shading and projecting) over the rate at which Embree alone traces exactly the same rays,
//    recorded during the bake and replayed in the same packets and streams, from cache as the
//    bake traces them (trace-only mode); and shading's time per ray, with what the target allows.
//    Embree's calls are also timed one by one inside a bake and in its replay: equal times show
//    that the rest of the bake is shading, not Embree slowed down by it. The same rays are also
//    traced in Embree's other forms of call (EmbreeCallForms.h), to see whether one would trace
//    them faster than the bake's own.
// 2. Stage breakdown: load, BVH, trace (the replay), shade (the rest of tracing), project, write.
// 3. Scaling: two threads against one; cost per probe, and the share of projection and write,
//    at 1×, 2× and 4× the probes; peak memory of `baker` processes at three grid sizes.
// 4. Sampling efficiency: rays per probe for 1 % irradiance RMSE (E for the six axis normals at
//    eight probes, against 2^19 Fibonacci rays) with the spherical Fibonacci set against
//    independent uniformly random directions.
// Default scene: the project's data/default_room.
#include <fmt/format.h>
#include <tbb/global_control.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <random>
#include <string>
#include <vector>

#include "bake/BakeJob.h"
#include "bake/PathIntegrator.h"
#include "bench/EmbreeCallForms.h"
#include "cli/CommandLine.h"
#include "common/Error.h"
#include "common/Timing.h"
#include "formats/VolumeWriter.h"
#include "images/ImageFiles.h"
#include "scene/RayRecorder.h"
#include "scene/RayTracer.h"

namespace baker {
namespace {

struct Options {
  std::string scene = std::string(BAKER_SOURCE_DIR) + "/data/default_room/default_room.gltf";
  std::string basis = "sh-l2";
  std::string baker = BAKER_BINARY;
  int rays = 256;
  double spacing = 0.0;
  bool json = false;
};

// Embree alone tracing the recorded rays, call by call as the bake made them. The bake traces
// each ray moments after making it, from cache; replaying straight out of a log of millions of
// rays instead streams it from memory, which on a shared host slowed the replay by up to 2.5×
// while Embree's time inside the bake held still. So the log is copied, untimed, into a small
// buffer a few thousand rays at a time, and only the Embree calls on it are timed.
double replaySeconds(const RayTracer& tracer, const RayLog& log) {
  constexpr std::size_t kChunkRays = 4096;
  std::vector<Ray> chunk;
  std::vector<Hit> hits(8);
  std::unique_ptr<bool[]> blocked;
  std::size_t blockedCapacity = 0;
  double seconds = 0.0;
  auto replay = [&](const std::vector<Ray>& rays, const std::vector<int>& sizes, auto traceCall) {
    std::size_t at = 0;
    for (std::size_t call = 0; call < sizes.size();) {
      std::size_t end = call, count = 0;
      while (end < sizes.size() && (end == call || count + std::size_t(sizes[end]) <= kChunkRays))
        count += std::size_t(sizes[end++]);
      chunk.assign(rays.begin() + std::ptrdiff_t(at), rays.begin() + std::ptrdiff_t(at + count));
      const auto start = std::chrono::steady_clock::now();
      std::size_t offset = 0;
      for (; call < end; ++call) {
        traceCall(chunk.data() + offset, sizes[call]);
        offset += std::size_t(sizes[call]);
      }
      seconds += secondsSince(start);
      at += count;
    }
  };
  replay(log.closest, log.packetSizes, [&](const Ray* rays, int size) { tracer.intersect8(rays, size, hits.data()); });
  replay(log.occlusion, log.streamSizes, [&](const Ray* rays, int size) {
    if (blockedCapacity < std::size_t(size)) {
      blockedCapacity = std::size_t(size);
      blocked.reset(new bool[blockedCapacity]);
    }
    tracer.occluded(rays, size, blocked.get());
  });
  return seconds;
}

// Rays per probe at which the relative RMSE reaches 1 %: interpolated in log-log between the
// measured counts, or, beyond the last, extrapolated along the power law fitted to the last
// three (*extrapolated set).
double raysForOnePercent(const std::vector<int>& counts, const std::vector<double>& errors, bool* extrapolated) {
  *extrapolated = false;
  if (errors.front() <= 0.01) return counts.front();
  for (std::size_t i = 1; i < counts.size(); ++i)
    if (errors[i] <= 0.01) {
      const double t = std::log(errors[i - 1] / 0.01) / std::log(errors[i - 1] / errors[i]);
      return std::exp(std::log(counts[i - 1]) + t * (std::log(counts[i]) - std::log(counts[i - 1])));
    }
  *extrapolated = true;
  const std::size_t n = counts.size();
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t i = n - 3; i < n; ++i) {
    const double x = std::log(counts[i]), y = std::log(errors[i]);
    sx += x, sy += y, sxx += x * x, sxy += x * y;
  }
  const double slope = (3 * sxy - sx * sy) / (3 * sxx - sx * sx), intercept = (sy - slope * sx) / 3;
  return slope < 0 ? std::exp((std::log(0.01) - intercept) / slope) : 0.0;
}

nlohmann::json run(const Options& o) {
  nlohmann::json out;
  // The image libraries are loaded before anything is timed, so that the load stage of a
  // textured scene times reading it, as before they moved into a module, and not 0.13 s of
  // dynamic linking that would also inflate the bake the stage shares are taken of.
  requireImageModule();
  BakeRequest request;
  request.scenePath = o.scene;
  request.basis = o.basis;
  request.quality.clear();
  request.rays = o.rays;
  if (o.spacing > 0.0) request.spacing = o.spacing;
  RayRecorder observer;
  const BakeJob job(request, &observer);
  const Scene& scene = job.scene();
  const RayTracer& tracer = job.tracer();
  const Basis* basis = &job.basis();
  const ProbeGrid& grid = job.grid();
  const BakeSettings& settings = job.settings();
  const double loadSeconds = job.loadSeconds(), bvhSeconds = job.bvhSeconds();
  auto stage = std::chrono::steady_clock::now();

  // 1, 2 and the thread scaling of 3: the bake recorded once, then rounds of a one-thread bake,
  // writing its volume, Embree alone replaying its rays, and a two-thread bake. Each is timed at
  // its best round: on a shared machine noise only ever adds time, and interleaving them keeps a
  // slow spell from favouring one of them. The write follows the bake directly, as in `baker`,
  // and meets the heap the bake leaves: timed after the replay instead, the writer that built
  // every grid at once measured 45–91 ms on default_room against 115–163 ms here (as `baker
  // --threads 1` reported too), because the replay had already touched memory it could reuse.
  constexpr int kRounds = 5;
  BakeStats stats, twoStats;
  double replay = std::numeric_limits<double>::infinity();
  double writeSeconds = std::numeric_limits<double>::infinity();
  const std::string path = (std::filesystem::temp_directory_path() / "bench_bake.vdb").string();
  Volume volume;
  // (TBB applies the smallest parallelism limit alive, so each limit lives only for its bake.)
  RayLog log;
  {
    tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
    observer.record(&log);
    bakeVolume(scene, tracer, *basis, grid, settings, nullptr);  // warms caches, records the rays
    observer.record(nullptr);
  }
  for (int round = 0; round < kRounds; ++round) {
    BakeStats s, s2;
    {
      tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
      volume = bakeVolume(scene, tracer, *basis, grid, settings, &s);
      stage = std::chrono::steady_clock::now();
      writeVolume(volume, *basis, VolumeOutput{path});
      writeSeconds = std::min(writeSeconds, secondsSince(stage));
      replay = std::min(replay, replaySeconds(tracer, log));
    }
    {
      tbb::global_control two(tbb::global_control::max_allowed_parallelism, 2);
      bakeVolume(scene, tracer, *basis, grid, settings, &s2);
    }
    if (round == 0 || s.traceSeconds < stats.traceSeconds) stats = s;
    if (round == 0 || s2.traceSeconds < twoStats.traceSeconds) twoStats = s2;
  }
  // Embree's own time inside a bake against replaying its rays, every call timed alike (a clock
  // read on either side of it, which adds the same to both): were shading to slow Embree down,
  // by evicting its BVH from cache or otherwise, the replay would understate what tracing costs
  // inside the bake, and the shading time would include the difference.
  double embreeInsideBake = 0.0, embreeReplaying = 0.0;
  {
    tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
    observer.timeEmbreeCalls(&embreeInsideBake);
    bakeVolume(scene, tracer, *basis, grid, settings, nullptr);
    observer.timeEmbreeCalls(&embreeReplaying);
    replaySeconds(tracer, log);
    observer.timeEmbreeCalls(nullptr);
  }
  out["embree_call_forms"] = embreeCallForms(tracer, log);
  constexpr double kThroughputTarget = 0.85;
  const double traced = double(stats.rays.total());
  const double bakeRate = traced / stats.traceSeconds, limitRate = traced / replay;
  const double shade = std::max(0.0, stats.traceSeconds - replay - stats.projectionSeconds);
  // The shading the target leaves room for: the bake may take replay / target in all, and
  // projection takes its share of that.
  const double shadeAtTarget = std::max(0.0, replay / kThroughputTarget - replay - stats.projectionSeconds);
  out["throughput"] = {{"rays", traced},
                       {"bake_mrays_per_second", bakeRate * 1e-6},
                       {"trace_only_mrays_per_second", limitRate * 1e-6},
                       {"ratio", bakeRate / limitRate},
                       {"shade_nanoseconds_per_ray", 1e9 * shade / traced},
                       {"shade_nanoseconds_per_ray_at_target", 1e9 * shadeAtTarget / traced},
                       {"embree_call_seconds_inside_bake", embreeInsideBake},
                       {"embree_call_seconds_replaying", embreeReplaying},
                       {"rounds", kRounds},
                       {"target", kThroughputTarget}};
  // The whole bake: load, BVH, operators, tracing (with shading and projection) and the write.
  auto bakeSeconds = [&](const BakeStats& s, double write) {
    return loadSeconds + bvhSeconds + s.operatorSeconds + s.traceSeconds + write;
  };
  auto projectionAndWriteShare = [&](const BakeStats& s, double write) {
    return (s.projectionSeconds + s.operatorSeconds + write) / bakeSeconds(s, write);
  };
  const double total = bakeSeconds(stats, writeSeconds);
  out["stages_seconds"] = {{"load", loadSeconds},   {"bvh", bvhSeconds},
                           {"operators", stats.operatorSeconds}, {"trace", replay},
                           {"shade", shade},        {"project", stats.projectionSeconds},
                           {"write", writeSeconds}, {"total", total}};
  out["projection_and_write_fraction"] = projectionAndWriteShare(stats, writeSeconds);
  out["projection_and_write_target"] = 0.05;
  out["threads"] = {{"one_thread_trace_seconds", stats.traceSeconds},
                    {"two_threads_trace_seconds", twoStats.traceSeconds},
                    {"speedup", stats.traceSeconds / twoStats.traceSeconds},
                    {"target", 1.9}};
  nlohmann::json perProbe = nlohmann::json::array();
  for (double factor : {1.0, 2.0, 4.0}) {
    tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
    const ProbeGrid finer = makeProbeGrid(scene.bounds, grid.spacing / std::cbrt(factor), kMaxBakeProbes);
    BakeStats s;
    const Volume finerVolume = bakeVolume(scene, tracer, *basis, finer, settings, &s);
    // Timed once, not at a best round: how the write's share falls as its fixed cost (every
    // grid's top node) spreads over more probes.
    stage = std::chrono::steady_clock::now();
    writeVolume(finerVolume, *basis, VolumeOutput{path});
    const double write = secondsSince(stage);
    perProbe.push_back({{"probes", s.probes}, {"trace_seconds", s.traceSeconds},
                        {"microseconds_per_probe", 1e6 * s.traceSeconds / double(s.probes)},
                        {"write_seconds", write},
                        {"projection_and_write_fraction", projectionAndWriteShare(s, write)}});
  }
  out["cost_against_probes"] = perProbe;
  std::filesystem::remove(path);
  nlohmann::json memory = nlohmann::json::array();
  for (double factor : {1.0, 8.0, 64.0}) {
    const std::string tmp = (std::filesystem::temp_directory_path() / "bench_bake_memory.vdb").string();
    const std::string command = "'" + o.baker + "' '" + o.scene + "' --quiet --json --rays 16 --spacing " +
                                std::to_string(grid.spacing / std::cbrt(factor)) + " --out '" + tmp + "'";
    FILE* pipe = ::popen(command.c_str(), "r");
    std::string text;
    char buffer[4096];
    while (pipe && std::fgets(buffer, sizeof buffer, pipe)) text += buffer;
    if (pipe) ::pclose(pipe);
    std::filesystem::remove(tmp);
    try {
      const nlohmann::json j = nlohmann::json::parse(text);
      memory.push_back({{"probes", j["probes"]}, {"peak_memory_mib", j["peak_memory_bytes"].get<double>() / 1048576.0}});
    } catch (const nlohmann::json::exception&) {
      memory.push_back({{"probes", nullptr}, {"error", "the baker run failed: " + command}});
    }
  }
  out["peak_memory_against_probes"] = memory;

  // 4. Sampling efficiency at a handful of probes, against 65536 Fibonacci rays.
  {
    TransportSettings transport = settings.transport;
    const PathIntegrator integrator(scene, tracer, transport);
    std::vector<Eigen::Vector3f> positions;
    for (int k = 0; k < 8; ++k)
      positions.push_back(grid.position((k * 5 + 1) % grid.dims.x(), (k * 3 + 1) % grid.dims.y(),
                                        (k * 7 + 2) % grid.dims.z())
                              .cast<float>());
    const std::vector<Eigen::Vector3f> normals = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    auto irradiance = [&](const Eigen::Vector3f& position, std::uint64_t id, const std::vector<Eigen::Vector3f>& dirs) {
      std::vector<Eigen::Vector3f> radiance(dirs.size());
      std::vector<float> sky(dirs.size());
      RayCounts counts;
      integrator.trace(position, id, dirs.data(), int(dirs.size()), radiance.data(), sky.data(), &counts);
      std::vector<Eigen::Vector3d> e(normals.size(), Eigen::Vector3d::Zero());
      for (std::size_t r = 0; r < dirs.size(); ++r)
        for (std::size_t n = 0; n < normals.size(); ++n)
          e[n] += radiance[r].cast<double>() * (4.0 * M_PI / dirs.size() * std::max(0.0f, normals[n].dot(dirs[r])));
      return e;
    };
    auto fibonacci = [](int n) {
      std::vector<Eigen::Vector3f> d;
      for (const Eigen::Vector3d& v : sphericalFibonacci(n).directions) d.push_back(v.cast<float>());
      return d;
    };
    std::vector<std::vector<Eigen::Vector3d>> reference;
    double mean = 0.0;
    for (std::size_t p = 0; p < positions.size(); ++p) {
      reference.push_back(irradiance(positions[p], 1000 + p, fibonacci(1 << 19)));
      for (const Eigen::Vector3d& e : reference.back()) mean += e.mean();
    }
    mean /= double(positions.size() * normals.size());
    std::mt19937 rng(7);
    std::normal_distribution<float> gauss;
    const std::vector<int> counts = {256, 1024, 4096, 16384, 65536};
    std::vector<double> fibonacciError, randomError;
    for (int n : counts) {
      double sf = 0.0, sr = 0.0;
      for (std::size_t p = 0; p < positions.size(); ++p) {
        std::vector<Eigen::Vector3f> random(n);
        for (Eigen::Vector3f& d : random) d = Eigen::Vector3f(gauss(rng), gauss(rng), gauss(rng)).normalized();
        const auto ef = irradiance(positions[p], p, fibonacci(n)), er = irradiance(positions[p], p, random);
        for (std::size_t k = 0; k < normals.size(); ++k) {
          sf += (ef[k] - reference[p][k]).squaredNorm() / 3.0;
          sr += (er[k] - reference[p][k]).squaredNorm() / 3.0;
        }
      }
      const double m = double(positions.size() * normals.size());
      fibonacciError.push_back(std::sqrt(sf / m) / mean);
      randomError.push_back(std::sqrt(sr / m) / mean);
    }
    bool fibonacciExtrapolated = false, randomExtrapolated = false;
    const double nf = raysForOnePercent(counts, fibonacciError, &fibonacciExtrapolated);
    const double nr = raysForOnePercent(counts, randomError, &randomExtrapolated);
    out["sampling_efficiency"] = {{"ray_counts", counts},
                                  {"fibonacci_relative_rmse", fibonacciError},
                                  {"random_relative_rmse", randomError},
                                  {"fibonacci_rays_for_1_percent", nf},
                                  {"fibonacci_extrapolated", fibonacciExtrapolated},
                                  {"random_rays_for_1_percent", nr},
                                  {"random_extrapolated", randomExtrapolated},
                                  {"ratio", nf > 0 && nr > 0 ? nr / nf : 0.0},
                                  {"target", 4.0}};
  }
  out["scene"] = std::filesystem::path(o.scene).filename().string();
  out["basis"] = o.basis;
  out["rays_per_probe"] = o.rays;
  out["probes"] = grid.probeCount();
  return out;
}

}  // namespace
}  // namespace baker

int main(int argc, char** argv) {
  baker::Options o;
  CLI::App app{"The bake's cost as ratios within one run: throughput against Embree alone, stages, thread "
               "and probe scaling, peak memory, sampling efficiency."};
  app.add_option("scene", o.scene, "glTF scene (default: data/default_room)")->check(CLI::ExistingFile);
  app.add_option("--rays", o.rays,
                 "rays per probe (the replay keeps every ray of a bake: about 130 MB at 256 on default_room)");
  app.add_option("--basis", o.basis, "basis (`baker bases` lists them)");
  app.add_option("--spacing", o.spacing, "probe spacing in scene units (default: the bake's own)");
  app.add_option("--baker", o.baker, "baker binary run for the peak-memory figures")->check(CLI::ExistingFile);
  app.add_flag("--json", o.json, "print the results as JSON");
  return baker::runGuarded("bench_bake", app, argc, argv, [&] {
    if (o.rays <= 0) throw baker::InputError(fmt::format("--rays must be positive, got {}", o.rays));
    if (!(o.spacing >= 0.0) || !std::isfinite(o.spacing))
      throw baker::InputError(fmt::format("--spacing must be positive (or 0 for the bake's own), got {}", o.spacing));
    const nlohmann::json result = baker::run(o);
    if (o.json) {
      std::cout << result.dump(2) << "\n";
      return 0;
    }
    std::cout << "throughput: bake " << result["throughput"]["bake_mrays_per_second"] << " Mrays/s, trace-only "
              << result["throughput"]["trace_only_mrays_per_second"] << " Mrays/s, ratio "
              << result["throughput"]["ratio"] << " (target " << result["throughput"]["target"] << "); shading "
              << result["throughput"]["shade_nanoseconds_per_ray"] << " ns per ray, "
              << result["throughput"]["shade_nanoseconds_per_ray_at_target"] << " at the target\n"
              << "Embree's calls, each timed: " << result["throughput"]["embree_call_seconds_inside_bake"]
              << " s inside a bake, " << result["throughput"]["embree_call_seconds_replaying"] << " s replaying it\n";
    std::cout << "Embree's call forms, time over the bake's own form: closest "
              << result["embree_call_forms"]["closest"].dump() << "; shadow " << result["embree_call_forms"]["shadow"].dump()
              << "\n";
    std::cout << "stages (s): " << result["stages_seconds"].dump() << "; projection + operators + write "
              << result["projection_and_write_fraction"] << " of the bake (target "
              << result["projection_and_write_target"] << ")\n";
    std::cout << "threads: 2 vs 1 speedup " << result["threads"]["speedup"] << " (target " << result["threads"]["target"]
              << ")\n";
    std::cout << "cost against probes: " << result["cost_against_probes"].dump() << "\n";
    std::cout << "peak memory: " << result["peak_memory_against_probes"].dump() << "\n";
    std::cout << "sampling: " << result["sampling_efficiency"].dump() << "\n";
    return 0;
  });
}
