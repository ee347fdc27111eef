#include "cli/AccuracyCommand.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "bake/Baker.h"
#include "bake/BasisRegistry.h"
#include "bake/ProbeValidity.h"
#include "cli/AccuracyPlot.h"
#include "cli/BakeOptions.h"
#include "cli/CommandLine.h"
#include "common/Error.h"
#include "common/Timing.h"
#include "formats/AtomicFile.h"

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

std::vector<int> parseIntList(const std::string& flag, const std::string& text) {
  std::vector<int> values;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    try {
      std::size_t used = 0;
      values.push_back(std::stoi(item, &used));
      if (used != item.size()) throw std::invalid_argument(item);
    } catch (const std::logic_error&) {
      throw InputError(fmt::format("{} {}: \"{}\" is not an integer", flag, text, item));
    }
  }
  if (values.empty()) throw InputError(fmt::format("{} is empty", flag));
  return values;
}

std::vector<std::string> parseNameList(const std::string& text) {
  std::vector<std::string> names;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ','))
    if (!item.empty()) names.push_back(item);
  if (names.empty()) throw InputError("--basis is empty");
  return names;
}

}  // namespace

int runAccuracyCommand(int argc, char** argv) {
  CLI::App app{"Measure what accuracy costs: bake every basis × rays × bounces combination and compare with a "
               "converged reference."};
  BakeOptions options;
  std::string basisList = "sh-l2,ad-srbf,ad-ycocg", raysList = "64,256,1024", bouncesList = "3", outDir = "accuracy";
  int referenceRays = 0, measured = 64;
  addBakeOptions(app, options, true);
  app.add_option("--basis", basisList, "comma-separated bases")->capture_default_str();
  app.add_option("--rays", raysList, "comma-separated ray counts per probe")->capture_default_str();
  app.add_option("--bounces", bouncesList, "comma-separated bounce counts")->capture_default_str();
  app.add_option("--out", outDir, "directory for accuracy.csv, accuracy.json, accuracy.svg, accuracy.md")
      ->capture_default_str();
  app.add_option("--reference-rays", referenceRays, "rays of the reference; default: 16 × the largest --rays-list");
  app.add_option("--probes", measured, "probes the error is measured at")->capture_default_str();
  return runGuarded("baker accuracy", app, argc, argv, [&]() {
    const std::vector<std::string> bases = parseNameList(basisList);
    const std::vector<int> raysValues = parseIntList("--rays", raysList);
    const std::vector<int> bouncesValues = parseIntList("--bounces", bouncesList);
    for (int r : raysValues)
      if (r <= 0 || r > (1 << 20)) throw InputError(fmt::format("--rays must be in 1..{}, got {}", 1 << 20, r));
    options.bounces = *std::max_element(bouncesValues.begin(), bouncesValues.end());
    for (const std::string& name : bases) makeBasis(name);  // unknown names fail before any work
    if (referenceRays == 0) referenceRays = std::min(1 << 20, 16 * *std::max_element(raysValues.begin(), raysValues.end()));
    if (measured <= 0) throw InputError(fmt::format("--probes must be positive, got {}", measured));
    std::filesystem::create_directories(outDir);

    PreparedBake prepared = prepareBake(app, options, std::cerr);
    const Scene& scene = *prepared.scene;
    const ProbeGrid& grid = prepared.grid;
    const std::vector<Eigen::Vector3f> normals = cubeNormals();

    // Where the error is measured: probes spread over the grid, placed as the bake places them.
    const ValidityOptions validityOptions;
    const std::vector<Eigen::Vector3f> testDirections = validityDirections(validityOptions);
    std::vector<std::int64_t> probes;
    std::vector<ProbeTask> tasks;
    const double stride = std::max(1.0, double(grid.probeCount()) / measured);
    for (double k = 0.0; k < double(grid.probeCount()) && int(probes.size()) < measured; k += stride) {
      const std::int64_t p = std::int64_t(k);
      const int i = int(p % grid.dims.x()), j = int((p / grid.dims.x()) % grid.dims.y()),
                z = int(p / (std::int64_t(grid.dims.x()) * grid.dims.y()));
      const Eigen::Vector3f position = grid.position(i, j, z).cast<float>();
      ProbePlacement placement;
      if (prepared.settings.transport.probeValidity)
        placement = placeProbe(*prepared.tracer, position, float(grid.spacing), testDirections, validityOptions, nullptr);
      if (placement.state == ProbeState::Invalid) continue;
      probes.push_back(p);
      tasks.push_back({position + placement.offset, std::uint64_t(p) + (std::uint64_t(1) << 40), 0});
    }
    if (probes.empty()) throw InputError(fmt::format("{}: no valid probe to measure at", options.scenePath));

    nlohmann::json rows = nlohmann::json::array();
    std::ostringstream csv;
    csv << "basis,rays,bounces,bake_seconds,operator_seconds,trace_seconds,relative_rmse,max_relative_error\n";
    std::map<std::string, AccuracyCurve> curves;
    for (int bounces : bouncesValues) {
      // The converged reference: the irradiance the samples of many more rays imply, before any basis.
      BakeSettings referenceSettings = prepared.settings;
      referenceSettings.rays = referenceRays;
      referenceSettings.transport.bounces = prepared.settings.transport.bounces > 0 ? bounces : 0;
      const auto referenceBasis = makeBasis("sh-l0");
      const ProbeBaker referenceBaker(scene, *prepared.tracer, *referenceBasis, referenceSettings, 1);
      std::vector<ProbeSamples> samples;
      std::vector<float> unusedCoefficients(tasks.size() * referenceBaker.coefficientsPerProbe());
      std::vector<float> unusedVisibility(tasks.size() * referenceBaker.visibilityPerProbe());
      RayCounts referenceRaysTraced;
      referenceBaker.bake(tasks, unusedCoefficients.data(), unusedVisibility.data(), &referenceRaysTraced, &samples);
      std::vector<Eigen::Vector3f> reference;
      double referenceMean = 0.0;
      for (const ProbeSamples& s : samples)
        for (const Eigen::Vector3f& n : normals) {
          reference.push_back(sampledIrradiance(s, n));
          referenceMean += reference.back().mean();
        }
      referenceMean /= double(reference.size());
      if (!(referenceMean > 0.0)) throw InputError(fmt::format("{}: the scene is black at every measured probe", options.scenePath));

      for (const std::string& name : bases)
        for (int rays : raysValues) {
          const std::unique_ptr<Basis> basis = makeBasis(name, options.sgSharpness);
          BakeSettings settings = prepared.settings;
          settings.rays = rays;
          settings.transport.bounces = referenceSettings.transport.bounces;
          const auto start = std::chrono::steady_clock::now();
          BakeStats stats;
          const Volume volume = bakeVolume(scene, *prepared.tracer, *basis, grid, settings, &stats);
          const double seconds = secondsSince(start);
          double sumSquares = 0.0, worst = 0.0;
          std::size_t k = 0;
          for (std::int64_t p : probes)
            for (const Eigen::Vector3f& n : normals) {
              const Eigen::Vector3f e = basis->reconstruct(volume.probe(p), n.cast<double>());
              const Eigen::Vector3f d = e - reference[k++];
              sumSquares += d.squaredNorm() / 3.0;
              worst = std::max(worst, double(d.cwiseAbs().maxCoeff()) / referenceMean);
            }
          const double rmse = std::sqrt(sumSquares / double(reference.size())) / referenceMean;
          rows.push_back({{"basis", name},
                          {"rays", rays},
                          {"bounces", settings.transport.bounces},
                          {"bake_seconds", seconds},
                          {"operator_seconds", stats.operatorSeconds},
                          {"trace_seconds", stats.traceSeconds},
                          {"relative_rmse", rmse},
                          {"max_relative_error", worst}});
          csv << fmt::format("{},{},{},{:.6f},{:.6f},{:.6f},{:.6g},{:.6g}\n", name, rays, settings.transport.bounces,
                             seconds, stats.operatorSeconds, stats.traceSeconds, rmse, worst);
          AccuracyCurve& curve = curves[fmt::format("{} ({} b.)", name, settings.transport.bounces)];
          curve.label = fmt::format("{} ({} b.)", name, settings.transport.bounces);
          curve.seconds.push_back(seconds);
          curve.error.push_back(rmse);
          curve.pointLabels.push_back(std::to_string(rays));
          std::cerr << fmt::format("{:<12} {:>7} rays {:>2} bounces: {:8.3f} s, relative RMSE {:.4g}\n", name, rays,
                                   settings.transport.bounces, seconds, rmse);
        }
    }

    const std::string sceneName = std::filesystem::path(options.scenePath).filename().string();
    const nlohmann::json report = {
        {"scene", sceneName},
        {"grid", {{"dims", {grid.dims.x(), grid.dims.y(), grid.dims.z()}}, {"spacing", grid.spacing}}},
        {"reference", {{"rays", referenceRays}, {"measured_probes", probes.size()}, {"normals", normals.size()},
                       {"quantity", "irradiance E(n) implied by the reference's samples, before any basis"}}},
        {"error", "relative RMSE: RMS over probes, 26 normals and RGB of (E - E_ref), over the mean of E_ref"},
        {"threads", options.threads},
        {"results", rows}};
    std::vector<AccuracyCurve> curveList;
    for (auto& [label, curve] : curves) curveList.push_back(curve);
    std::ostringstream md;
    md << fmt::format("Accuracy against bake time for `{}` ({} × {} × {} probes, spacing {:.3g}); error measured at {} "
                      "probes × 26 normals against {} rays per probe.\n\n",
                      sceneName, grid.dims.x(), grid.dims.y(), grid.dims.z(), grid.spacing, probes.size(), referenceRays);
    md << "| basis | rays | bounces | bake s | relative RMSE | max relative error |\n|---|---|---|---|---|---|\n";
    for (const nlohmann::json& r : rows)
      md << fmt::format("| {} | {} | {} | {:.3f} | {:.4f} | {:.4f} |\n", r["basis"].get<std::string>(),
                        r["rays"].get<int>(), r["bounces"].get<int>(), r["bake_seconds"].get<double>(),
                        r["relative_rmse"].get<double>(), r["max_relative_error"].get<double>());
    const std::pair<std::string, std::string> outputs[] = {
        {"accuracy.csv", csv.str()},
        {"accuracy.json", report.dump(2) + "\n"},
        {"accuracy.svg", accuracyPlotSvg(curveList, "Irradiance error against bake time: " + sceneName)},
        {"accuracy.md", md.str()}};
    for (const auto& [file, text] : outputs) {
      AtomicFile out((std::filesystem::path(outDir) / file).string());
      std::ofstream(out.temporaryPath()) << text;
      out.commit();
    }
    std::cout << md.str();
    return 0;
  });
}

}  // namespace baker
