#include "cli/ProbeCommand.h"

#include <fmt/format.h>

#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "bake/ProbeBaker.h"
#include "bake/ProbeValidity.h"
#include "cli/BakeOptions.h"
#include "cli/CommandLine.h"
#include "common/Error.h"
#include "formats/VolumeSampler.h"

namespace baker {
namespace {

const char* const kAxisNames[6] = {"+X", "-X", "+Y", "-Y", "+Z", "-Z"};

Eigen::Vector3f axis(int a) {
  Eigen::Vector3f n = Eigen::Vector3f::Zero();
  n[a / 2] = a % 2 == 0 ? 1.0f : -1.0f;
  return n;
}

nlohmann::json vec(const Eigen::Vector3f& v) { return {v.x(), v.y(), v.z()}; }

}  // namespace

int runProbeCommand(int argc, char** argv) {
  CLI::App app{"Bake single probes and print what they receive."};
  BakeOptions options;
  std::vector<std::string> at;
  bool json = false;
  addBakeOptions(app, options);
  app.add_option("--at", at, "probe position x,y,z in world units (repeatable)")->required()->allow_extra_args(false);
  app.add_flag("--json", json, "print the probes as JSON on stdout");

  return runGuarded("baker probe", app, argc, argv, [&]() {
    std::vector<Eigen::Vector3f> positions;
    for (const std::string& text : at) positions.push_back(parseTriple("--at", text).cast<float>());
    PreparedBake prepared = prepareBake(app, options, std::cerr);
    const Basis& basis = *prepared.basis;
    const ProbeBaker probeBaker(*prepared.scene, *prepared.tracer, basis, prepared.settings, 1);

    RayCounts counts;
    const ValidityOptions validityOptions;
    const std::vector<Eigen::Vector3f> testDirections = validityDirections(validityOptions);
    std::vector<ProbePlacement> placements;
    std::vector<ProbeTask> tasks;
    for (std::size_t i = 0; i < positions.size(); ++i) {
      ProbePlacement placement;
      if (prepared.settings.transport.probeValidity)
        placement = placeProbe(*prepared.tracer, positions[i], float(prepared.grid.spacing), testDirections,
                               validityOptions, &counts.validity);
      placements.push_back(placement);
      tasks.push_back({positions[i] + placement.offset, std::uint64_t(i), 0});
    }
    std::vector<float> coefficients(tasks.size() * probeBaker.coefficientsPerProbe());
    std::vector<float> visibility(tasks.size() * probeBaker.visibilityPerProbe());
    std::vector<ProbeSamples> samples;
    probeBaker.bake(tasks, coefficients.data(), visibility.data(), &counts, &samples);

    for (float c : coefficients)
      if (!std::isfinite(c)) throw NumericalError("a probe's coefficients are not finite: the scene's radiance overflows float");
    nlohmann::json probes = nlohmann::json::array();
    for (std::size_t i = 0; i < tasks.size(); ++i) {
      const float* c = coefficients.data() + i * probeBaker.coefficientsPerProbe();
      const float* v = visibility.data() + i * probeBaker.visibilityPerProbe();
      nlohmann::json fromBasis, fromSamples, visibilityByNormal;
      for (int a = 0; a < 6; ++a) {
        const Eigen::Vector3f n = axis(a);
        fromBasis[kAxisNames[a]] = vec(basis.reconstruct(c, n.cast<double>()));
        fromSamples[kAxisNames[a]] = vec(sampledIrradiance(samples[i], n));
        visibilityByNormal[kAxisNames[a]] = reconstructVisibility(basis, v, n.cast<double>());
      }
      double escaped = 0.0;
      for (std::size_t r = 0; r < samples[i].visibility.size(); ++r)
        escaped += samples[i].weights[r] * samples[i].visibility[r];
      probes.push_back({{"position", vec(positions[i])},
                        {"baked_position", vec(tasks[i].position)},
                        {"offset", vec(placements[i].offset)},
                        {"state", probeStateName(placements[i].state)},
                        {"valid", placements[i].state != ProbeState::Invalid},
                        {"backface_ratio", placements[i].backfaceRatio},
                        {"rays", std::int64_t(samples[i].radiance.size())},
                        {"coefficients", std::vector<float>(c, c + probeBaker.coefficientsPerProbe())},
                        {"visibility_coefficients", std::vector<float>(v, v + probeBaker.visibilityPerProbe())},
                        {"irradiance", fromBasis},
                        {"irradiance_from_samples", fromSamples},
                        {"sky_visibility", escaped / (4.0 * M_PI)},
                        {"sky_visibility_by_normal", visibilityByNormal}});
    }

    if (json) {
      const nlohmann::json j = {{"scene", options.scenePath},
                                {"basis", basis.name()},
                                {"rays", prepared.settings.rays},
                                {"quality", qualityName(options, prepared.settings)},
                                {"target_relative_error", prepared.settings.convergence.targetError},
                                {"bounces", prepared.settings.transport.bounces},
                                {"seed", options.seed},
                                {"plan", planJson(prepared.plan)},
                                {"ray_counts", rayCountsJson(counts)},
                                {"probes", probes}};
      std::cout << j.dump(2) << "\n";
      return 0;
    }
    for (const nlohmann::json& p : probes) {
      std::cout << fmt::format(
          "probe at ({}): {} (back-face ratio {:.3f}), baked at ({}) with {} rays, sky visibility {:.4f}\n",
          fmt::join(p["position"].get<std::vector<float>>(), ", "), p["state"].get<std::string>(),
          p["backface_ratio"].get<float>(), fmt::join(p["baked_position"].get<std::vector<float>>(), ", "),
          p["rays"].get<std::int64_t>(), p["sky_visibility"].get<double>());
      std::cout << "  normal  E from the basis (r, g, b)            E from the samples (r, g, b)          sky\n";
      for (const char* name : kAxisNames) {
        const auto b = p["irradiance"][name].get<std::vector<float>>();
        const auto s = p["irradiance_from_samples"][name].get<std::vector<float>>();
        std::cout << fmt::format("  {:<6}  {:>10.5g} {:>10.5g} {:>10.5g}    {:>10.5g} {:>10.5g} {:>10.5g}    {:.4f}\n", name,
                                 b[0], b[1], b[2], s[0], s[1], s[2], p["sky_visibility_by_normal"][name].get<double>());
      }
      std::cout << fmt::format("  coefficients ({}): {}\n", basis.name(),
                               fmt::join(p["coefficients"].get<std::vector<float>>(), " "));
    }
    return 0;
  });
}

}  // namespace baker
