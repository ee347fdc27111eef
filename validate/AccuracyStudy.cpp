#include "validate/AccuracyStudy.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "basis/BasisRegistry.h"
#include "common/Error.h"
#include "common/Timing.h"
#include "formats/VolumeReconstruction.h"
#include "validate/AccuracyPlot.h"

namespace baker {
namespace {

// The normals every error is measured over: the 26 directions to the faces, edges and corners
// of a cube around the probe.
std::vector<Eigen::Vector3f> cubeNormals() {
  std::vector<Eigen::Vector3f> normals;
  for (int x = -1; x <= 1; ++x)
    for (int y = -1; y <= 1; ++y)
      for (int z = -1; z <= 1; ++z)
        if (x || y || z) normals.push_back(Eigen::Vector3f(float(x), float(y), float(z)).normalized());
  return normals;
}

// Where the error is measured: probes spread evenly over the grid, placed as the bake places
// them, the invalid ones left out; their ids are apart from every grid probe's.
std::vector<ProbeTask> measuredTasks(const BakeJob& job, int measured, std::vector<std::int64_t>& probes) {
  const ProbeGrid& grid = job.grid();
  std::vector<std::int64_t> candidates;
  std::vector<Eigen::Vector3f> positions;
  const double stride = std::max(1.0, double(grid.probeCount()) / measured);
  for (double k = 0.0; k < double(grid.probeCount()); k += stride) {
    const std::int64_t p = std::int64_t(k);
    candidates.push_back(p);
    positions.push_back(grid.position(p).cast<float>());
  }
  const std::vector<ProbePlacement> placements =
      placeProbes(job.tracer(), job.settings().transport, grid.spacing, positions, nullptr);
  std::vector<ProbeTask> tasks;
  for (std::size_t c = 0; c < candidates.size() && int(probes.size()) < measured; ++c) {
    if (placements[c].state == ProbeState::Invalid) continue;
    probes.push_back(candidates[c]);
    tasks.push_back({positions[c] + placements[c].offset, std::uint64_t(candidates[c]) + (std::uint64_t(1) << 40), 0});
  }
  if (probes.empty()) throw InputError(fmt::format("{}: no valid probe to measure at", job.request().scenePath));
  return tasks;
}

// The converged reference: the irradiance the samples of many more rays imply, before any basis.
std::vector<Eigen::Vector3f> referenceIrradiance(const BakeJob& job, const std::vector<ProbeTask>& tasks,
                                                 const BakeSettings& settings, const std::vector<Eigen::Vector3f>& normals) {
  const BakedProbes baked = bakeTasks(job.scene(), job.tracer(), *makeBasis("sh-l0"), settings, tasks);
  std::vector<Eigen::Vector3f> reference;
  for (const ProbeSamples& s : baked.samples)
    for (const Eigen::Vector3f& n : normals) reference.push_back(sampledIrradiance(s, n));
  return reference;
}

}  // namespace

void validateAccuracyPlan(const AccuracyPlan& plan) {
  if (plan.bases.empty()) throw SettingError("basis", "is empty");
  for (const std::string& name : plan.bases)  // unknown names fail before any work
    if (makeBasis(name)->hemisphere())
      throw SettingError("basis", fmt::format("{} holds radiance over one hemisphere: the study reads every basis at "
                                              "normals over the whole sphere, which it cannot serve",
                                              name));
  if (plan.rays.empty()) throw SettingError("rays", "is empty");
  for (int r : plan.rays)
    if (r <= 0 || r > kMaxRaysPerProbe)
      throw SettingError("rays", fmt::format("must be in 1..{}, got {}", kMaxRaysPerProbe, r));
  if (plan.bounces.empty()) throw SettingError("bounces", "is empty");
  if (plan.referenceRays < 0 || plan.referenceRays > kMaxRaysPerProbe)
    throw SettingError("reference_rays", fmt::format("must be in 1..{}, got {}", kMaxRaysPerProbe, plan.referenceRays));
  if (plan.measuredProbes <= 0)
    throw SettingError("probes", fmt::format("must be positive, got {}", plan.measuredProbes));
}

AccuracyStudy measureAccuracy(const BakeJob& job, AccuracyPlan plan, const std::function<void(const AccuracyRow&)>& onRow) {
  validateAccuracyPlan(plan);
  if (plan.referenceRays == 0)
    plan.referenceRays = std::min(kMaxRaysPerProbe, 16 * *std::max_element(plan.rays.begin(), plan.rays.end()));
  const std::vector<Eigen::Vector3f> normals = cubeNormals();
  AccuracyStudy study;
  study.sceneName = std::filesystem::path(job.request().scenePath).filename().string();
  study.grid = job.grid();
  study.referenceRays = plan.referenceRays;
  study.threads = job.request().threads;
  study.normals = normals.size();
  std::vector<std::int64_t> probes;
  const std::vector<ProbeTask> tasks = measuredTasks(job, plan.measuredProbes, probes);
  study.measuredProbes = probes.size();

  for (int bounces : plan.bounces) {
    BakeSettings settings = job.settings();
    settings.rays = plan.referenceRays;
    settings.transport.bounces = job.settings().transport.bounces > 0 ? bounces : 0;
    const std::vector<Eigen::Vector3f> reference = referenceIrradiance(job, tasks, settings, normals);
    double referenceMean = 0.0;
    for (const Eigen::Vector3f& e : reference) referenceMean += e.mean();
    referenceMean /= double(reference.size());
    if (!(referenceMean > 0.0))
      throw InputError(fmt::format("{}: the scene is black at every measured probe", job.request().scenePath));

    for (const std::string& name : plan.bases)
      for (int rays : plan.rays) {
        const VolumeReconstruction reading(makeBasis(name, job.request().basisParameters()), settings.projection.signal);
        settings.rays = rays;
        const auto start = std::chrono::steady_clock::now();
        BakeStats stats;
        const Volume volume = bakeVolume(job.scene(), job.tracer(), reading.basis(), job.grid(), settings, &stats);
        AccuracyRow row{name, rays, settings.transport.bounces, secondsSince(start), stats.operatorSeconds,
                        stats.traceSeconds};
        double sumSquares = 0.0;
        std::size_t k = 0;
        for (std::int64_t p : probes)
          for (const Eigen::Vector3f& n : normals) {
            const Eigen::Vector3f d = reading.irradiance(volume.probe(p), n.cast<double>()) - reference[k++];
            sumSquares += d.squaredNorm() / 3.0;
            row.maxRelativeError = std::max(row.maxRelativeError, double(d.cwiseAbs().maxCoeff()) / referenceMean);
          }
        row.relativeRmse = std::sqrt(sumSquares / double(reference.size())) / referenceMean;
        study.rows.push_back(row);
        if (onRow) onRow(row);
      }
  }
  return study;
}

std::vector<std::pair<std::string, std::string>> accuracyReports(const AccuracyStudy& study) {
  const ProbeGrid& grid = study.grid;
  nlohmann::json rows = nlohmann::json::array();
  std::ostringstream csv, md;
  std::map<std::string, AccuracyCurve> curves;
  csv << "basis,rays,bounces,bake_seconds,operator_seconds,trace_seconds,relative_rmse,max_relative_error\n";
  md << fmt::format("Accuracy against bake time for `{}` ({} × {} × {} probes, spacing {:.3g}); error measured at {} "
                    "probes × 26 normals against {} rays per probe.\n\n",
                    study.sceneName, grid.dims.x(), grid.dims.y(), grid.dims.z(), grid.spacing, study.measuredProbes,
                    study.referenceRays);
  md << "| basis | rays | bounces | bake s | relative RMSE | max relative error |\n|---|---|---|---|---|---|\n";
  for (const AccuracyRow& r : study.rows) {
    rows.push_back({{"basis", r.basis},
                    {"rays", r.rays},
                    {"bounces", r.bounces},
                    {"bake_seconds", r.bakeSeconds},
                    {"operator_seconds", r.operatorSeconds},
                    {"trace_seconds", r.traceSeconds},
                    {"relative_rmse", r.relativeRmse},
                    {"max_relative_error", r.maxRelativeError}});
    csv << fmt::format("{},{},{},{:.6f},{:.6f},{:.6f},{:.6g},{:.6g}\n", r.basis, r.rays, r.bounces, r.bakeSeconds,
                       r.operatorSeconds, r.traceSeconds, r.relativeRmse, r.maxRelativeError);
    md << fmt::format("| {} | {} | {} | {:.3f} | {:.4f} | {:.4f} |\n", r.basis, r.rays, r.bounces, r.bakeSeconds,
                      r.relativeRmse, r.maxRelativeError);
    const std::string label = fmt::format("{} ({} b.)", r.basis, r.bounces);
    AccuracyCurve& curve = curves[label];
    curve.label = label;
    curve.seconds.push_back(r.bakeSeconds);
    curve.error.push_back(r.relativeRmse);
    curve.pointLabels.push_back(std::to_string(r.rays));
  }
  const nlohmann::json report = {
      {"scene", study.sceneName},
      {"grid", {{"dims", {grid.dims.x(), grid.dims.y(), grid.dims.z()}}, {"spacing", grid.spacing}}},
      {"reference", {{"rays", study.referenceRays}, {"measured_probes", study.measuredProbes}, {"normals", study.normals},
                     {"quantity", "irradiance E(n) implied by the reference's samples, before any basis"}}},
      {"error", "relative RMSE: RMS over probes, 26 normals and RGB of (E - E_ref), over the mean of E_ref"},
      {"threads", study.threads},
      {"results", rows}};
  std::vector<AccuracyCurve> curveList;
  for (auto& [label, curve] : curves) curveList.push_back(curve);
  return {{"accuracy.csv", csv.str()},
          {"accuracy.json", report.dump(2) + "\n"},
          {"accuracy.svg", accuracyPlotSvg(curveList, "Irradiance error against bake time: " + study.sceneName)},
          {"accuracy.md", md.str()}};
}

}  // namespace baker
