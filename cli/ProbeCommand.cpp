#include "cli/ProbeCommand.h"

#include <fmt/format.h>

#include <iostream>
#include <optional>
#include <nlohmann/json.hpp>
#include <sstream>

#include "bake/BakeJob.h"
#include "basis/BasisRegistry.h"
#include "basis/GgxLobe.h"
#include "cli/BakeOptions.h"
#include "cli/CommandLine.h"
#include "cli/SpecularFlags.h"
#include "common/Error.h"
#include "formats/VolumeReconstruction.h"
#include "volume/ProbeState.h"

namespace baker {
namespace {

const char* const kAxisNames[6] = {"+X", "-X", "+Y", "-Y", "+Z", "-Z"};

Eigen::Vector3f axis(int a) {
  Eigen::Vector3f n = Eigen::Vector3f::Zero();
  n[a / 2] = a % 2 == 0 ? 1.0f : -1.0f;
  return n;
}

nlohmann::json vec(const Eigen::Vector3f& v) { return {v.x(), v.y(), v.z()}; }

nlohmann::json probeJson(const VolumeReconstruction& reading, const BakedProbes& baked, const Eigen::Vector3f& position, std::size_t i) {
  const float* c = baked.probe(i);
  const float* v = baked.probeVisibility(i);
  const ProbeSamples& samples = baked.samples[i];
  const ProbePlacement& placement = baked.placements[i];
  nlohmann::json fromBasis, fromSamples, visibilityByNormal;
  for (int a = 0; a < 6; ++a) {
    const Eigen::Vector3f n = axis(a);
    fromBasis[kAxisNames[a]] = vec(reading.irradiance(c, n.cast<double>()));
    fromSamples[kAxisNames[a]] = vec(sampledIrradiance(samples, n));
    visibilityByNormal[kAxisNames[a]] = reading.skyVisibility(v, n.cast<double>());
  }
  double escaped = 0.0;
  for (std::size_t r = 0; r < samples.visibility.size(); ++r) escaped += samples.weights[r] * samples.visibility[r];
  return {{"position", vec(position)},
          {"baked_position", vec(baked.tasks[i].position)},
          {"offset", vec(placement.offset)},
          {"state", probeStateName(placement.state)},
          {"valid", placement.state != ProbeState::Invalid},
          {"backface_ratio", placement.backfaceRatio},
          {"rays", std::int64_t(samples.radiance.size())},
          {"coefficients", std::vector<float>(c, c + baked.coefficientsPerProbe)},
          {"visibility_coefficients", std::vector<float>(v, v + baked.visibilityPerProbe)},
          {"irradiance", fromBasis},
          {"irradiance_from_samples", fromSamples},
          {"sky_visibility", escaped / (4.0 * M_PI)},
          {"sky_visibility_by_normal", visibilityByNormal}};
}

// Specular for one normal and view from the basis and, as the reference, from the probe's own
// samples; null when not asked for.
nlohmann::json specularJson(const std::optional<SpecularRequest>& request, const Eigen::Vector3d& normal,
                            const VolumeReconstruction& reading, const BakedProbes& baked, std::size_t i) {
  if (!request) return nullptr;
  const SampledSpecular reference = sampledSpecular(baked.samples[i], GgxLobe(normal, request->view, request->roughness));
  return {{"normal", vec(normal.cast<float>())},
          {"view", vec(request->view.cast<float>())},
          {"roughness", request->roughness},
          {"value", vec(reading.specular(baked.probe(i), normal, request->view, request->roughness).value)},
          // No set of rays holds the mirror's (or any lobe's they all miss) reference.
          {"from_samples", reference.rayCoverage > 0.0 ? vec(reference.value) : nlohmann::json()},
          {"ray_coverage", reference.rayCoverage},
          {"albedo", reference.albedo}};
}

std::string specularLine(const nlohmann::json& s) {
  const auto numbers = [&](const char* key, const char* format) {
    return s[key].is_null() ? std::string("none")
                            : fmt::format(fmt::runtime(format), fmt::join(s[key].get<std::vector<float>>(), ", "));
  };
  return fmt::format("  specular S (roughness {}, normal ({}), view ({})): from the basis ({}), from the samples ({}), "
                     "the rays covering {:.3f} of the lobe\n",
                     s["roughness"].get<double>(), numbers("normal", "{}"), numbers("view", "{}"),
                     numbers("value", "{:.5g}"), numbers("from_samples", "{:.5g}"), s["ray_coverage"].get<double>());
}

}  // namespace

int runProbeCommand(int argc, char** argv) {
  CLI::App app{"Bake single probes and print what they receive."};
  BakeOptions options;
  std::vector<std::string> at;
  bool json = false;
  addBakeOptions(app, options);
  app.add_option("--at", at, "probe position x,y,z in world units (repeatable)")->required()->allow_extra_args(false);
  app.add_flag("--json", json, "print the probes as JSON on stdout");
  SpecularFlags specularFlags;
  specularFlags.addTo(app);
  std::string normalText;
  app.add_option("--normal", normalText, "with --roughness and --view: the surface normal x,y,z; default: the view");

  return runGuarded("baker probe", app, argc, argv, [&]() {
    std::vector<Eigen::Vector3f> positions;
    for (const std::string& text : at) positions.push_back(parseTriple("--at", text).cast<float>());
    const std::optional<SpecularRequest> specular = specularRequest(specularFlags);
    if (!normalText.empty() && !specular) throw InputError("--normal goes with --roughness and --view");
    // Without --normal the surface faces the viewer; without specular no normal is read.
    const Eigen::Vector3d normal = !normalText.empty() ? parseDirection("--normal", normalText)
                                   : specular         ? specular->view
                                                      : Eigen::Vector3d::UnitY();
    if (specular && parseStoredSignal(options.request.signal) != StoredSignal::Radiance)
      throw InputError("--roughness and --view read specular from radiance: add --signal radiance");
    const std::unique_ptr<BakeJob> job = prepareBake(app, options, std::cerr);
    const Basis& basis = job->basis();
    const VolumeReconstruction reading(makeBasisLike(basis),
                                       job->settings().projection.signal);
    const BakedProbes baked = job->probesAt(positions);
    nlohmann::json probes = nlohmann::json::array();
    for (std::size_t i = 0; i < positions.size(); ++i) {
      probes.push_back(probeJson(reading, baked, positions[i], i));
      probes.back()["specular"] = specularJson(specular, normal, reading, baked, i);
    }

    if (json) {
      const nlohmann::json j = {{"scene", job->request().scenePath},
                                {"basis", basis.name()},
                                {"signal", storedSignalName(reading.signal())},
                                {"rays", job->settings().rays},
                                {"quality", qualityName(job->request())},
                                {"target_relative_error", job->settings().convergence.targetError},
                                {"bounces", job->settings().transport.bounces},
                                {"seed", job->request().seed},
                                {"plan", planJson(job->plan())},
                                {"ray_counts", rayCountsJson(baked.rays)},
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
      if (!p["specular"].is_null()) std::cout << specularLine(p["specular"]);
      std::cout << fmt::format("  coefficients ({}): {}\n", basis.name(),
                               fmt::join(p["coefficients"].get<std::vector<float>>(), " "));
    }
    return 0;
  });
}

}  // namespace baker
