#include "cli/EnvCommand.h"

#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "basis/BasisRegistry.h"
#include "cli/CommandLine.h"
#include "common/Error.h"
#include "formats/AtomicFile.h"
#include "images/RgbImage.h"
#include "validate/IrradianceFit.h"
#include "validate/IrradianceReference.h"
#include "validate/LatLongEnvironment.h"
#include "validate/SpecularOnEnvironment.h"
#include "validate/SphereSignals.h"

namespace baker {
namespace {

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// E/π, the quantity the RMSE measures, as an image.
RgbImage toImage(const LatLongEnvironment& env, const Eigen::MatrixX3d& irradiance) {
  RgbImage image(env.width(), env.height());
  for (int t = 0; t < env.texelCount(); ++t)
    for (int c = 0; c < 3; ++c) image.pixels[3 * std::size_t(t) + c] = float(irradiance(t, c) / M_PI);
  return image;
}

// Writes reference, reconstruction and error (reconstruction − reference) of E/π as float EXR
// and as sRGB PNG. Reference and reconstruction share one exposure that maps the reference's
// mean to 0.18 (mid grey); the error PNG shows |error| scaled so that the largest is white.
// Every file goes to a temporary name first, and all are renamed once all are complete.
std::vector<std::string> writeImages(const std::string& dir, const LatLongEnvironment& env,
                                     const Eigen::MatrixX3d& reference, const Eigen::MatrixX3d& reconstruction) {
  const double referenceMean = reference.mean() / M_PI;
  const double exposure = referenceMean > 0.0 ? 0.18 / referenceMean : 1.0;
  const Eigen::MatrixX3d error = reconstruction - reference;
  const double errorMax = error.cwiseAbs().maxCoeff() / M_PI;
  struct Output {
    const char* name;
    const Eigen::MatrixX3d values, shown;
    double exposure;
  };
  const Output outputs[] = {{"reference", reference, reference, exposure},
                            {"reconstruction", reconstruction, reconstruction, exposure},
                            {"error", error, error.cwiseAbs(), errorMax > 0.0 ? 1.0 / errorMax : 1.0}};

  std::vector<std::unique_ptr<AtomicFile>> files;
  std::vector<std::string> paths;
  for (const Output& output : outputs) {
    const std::string base = (std::filesystem::path(dir) / output.name).string();
    paths.push_back(base + ".exr");
    files.push_back(std::make_unique<AtomicFile>(paths.back()));
    writeExr(toImage(env, output.values), files.back()->temporaryPath());
    paths.push_back(base + ".png");
    files.push_back(std::make_unique<AtomicFile>(paths.back()));
    writeSrgbPng(toImage(env, output.shown), output.exposure, files.back()->temporaryPath());
  }
  for (const auto& file : files) file->commit();
  return paths;
}


// The roughness the radiance report reads specular at (issue 28's).
const std::vector<double> kRoughness = {0.1, 0.3, 0.6, 1.0};

int reportRadiance(const Basis& basis, const std::string& probePath, bool upward, bool json) {
  const auto start = std::chrono::steady_clock::now();
  const LatLongEnvironment env = LatLongEnvironment::load(probePath);
  // A hemispherical basis is read only where it holds the light: surfaces facing its axis.
  std::optional<Eigen::Vector3d> up = basis.hemisphere();
  if (!up && upward) up = Eigen::Vector3d::UnitY();
  const std::vector<SpecularFrame> chosen = up ? upwardFrames(*up) : specularFrames();
  const std::vector<EnvironmentSpecularScore> scores = scoreSpecularOnEnvironment(basis, env, probePath, kRoughness, chosen);
  const std::size_t frames = chosen.size();
  if (json) {
    nlohmann::json fits = nlohmann::json::object();
    for (const EnvironmentSpecularScore& s : scores) {
      nlohmann::json specular = nlohmann::json::array();
      for (const std::optional<double>& e : s.specularRelativeRmse) specular.push_back(e ? nlohmann::json(*e) : nlohmann::json());
      fits[fitMethodName(s.fit)] = {{"bytes_per_probe", s.bytesPerProbe},
                                    {"diffuse_relative_rmse", s.diffuseRelativeRmse},
                                    {"specular_relative_rmse", specular}};
    }
    nlohmann::json report = {{"probe", probePath},
                             {"width", env.width()},
                             {"height", env.height()},
                             {"basis", basis.name()},
                             {"signal", "radiance"},
                             {"coefficients", basis.totalCoefficients()},
                             {"frames", frames},
                             {"normals", up ? "up" : "sphere"},
                             {"roughness", kRoughness},
                             {"reference", "exact integrals over all texels of the image"},
                             {"fits", fits},
                             {"seconds", secondsSince(start)}};
    report.update(parametersJson(basis.parameters()));
    std::cout << report.dump(2) << "\n";
    return 0;
  }
  std::cout << fmt::format("probe   {} ({} x {} texels)\n", probePath, env.width(), env.height());
  std::cout << fmt::format("basis   {} ({} coefficients), radiance fitted at {} x {} texels\n", basis.name(),
                           basis.totalCoefficients(), kSignalWidth, kSignalWidth / 2);
  std::cout << fmt::format("relative RMSE against the exact integrals over the image, {} normal/view pairs ({}):\n",
                           frames, up ? "normal up" : "normals over the sphere");
  std::cout << fmt::format("  {:<13} {:>7} {:>9}", "fit", "B/probe", "diffuse");
  for (double r : kRoughness) std::cout << fmt::format(" {:>9}", fmt::format("r = {}", r));
  std::cout << "\n";
  for (const EnvironmentSpecularScore& s : scores) {
    std::cout << fmt::format("  {:<13} {:>7} {:>8.2f}%", fitMethodName(s.fit), s.bytesPerProbe, 100.0 * s.diffuseRelativeRmse);
    for (const std::optional<double>& e : s.specularRelativeRmse)
      std::cout << (e ? fmt::format(" {:>8.2f}%", 100.0 * *e) : fmt::format(" {:>9}", "-"));
    std::cout << "\n";
  }
  std::cout << fmt::format("{:.2f} s\n", secondsSince(start));
  return 0;
}

// The paper's irradiance fits (section 4) and their RMSE against the exact texel sum.
int reportIrradiance(const Basis& basis, const std::string& probePath, const std::string& outDir, bool json) {
  std::error_code ec;
  if (!outDir.empty() && !std::filesystem::is_directory(outDir, ec))
    throw InputError(fmt::format("--out-dir {}: no such directory", outDir));

  const auto start = std::chrono::steady_clock::now();
  const LatLongEnvironment env = LatLongEnvironment::load(probePath);
  auto stage = std::chrono::steady_clock::now();
  const Eigen::MatrixX3d reference = exactIrradiance(env);
  const double referenceSeconds = secondsSince(stage);
  stage = std::chrono::steady_clock::now();
  const std::vector<IrradianceFit> fits = fitIrradiance(basis, env, reference);
  const double fitSeconds = secondsSince(stage);
  const std::vector<std::string> written =
      outDir.empty() ? std::vector<std::string>{} : writeImages(outDir, env, reference, fits.front().irradiance);

  if (json) {
    nlohmann::json rmse = nlohmann::json::object(), conditioning = nlohmann::json::object();
    for (const IrradianceFit& fit : fits) {
      rmse[fit.method] = fit.rmse;
      if (fit.conditionNumber > 0) conditioning[fit.method] = fit.conditionNumber;
    }
    nlohmann::json report = {
        {"probe", probePath},
        {"width", env.width()},
        {"height", env.height()},
        {"basis", basis.name()},
        {"color_space", colorSpaceName(basis.colorSpace())},
        {"coefficients", basis.totalCoefficients()},
        {"coefficients_per_lookup", basis.coefficientsPerLookup()},
        {"quantity", "irradiance / pi"},
        {"reference", "exact sum over all texels"},
        {"rmse", rmse},
        {"seconds", {{"total", secondsSince(start)}, {"reference", referenceSeconds}, {"fit", fitSeconds}}},
    };
    if (!conditioning.empty()) report["gram_condition_number"] = conditioning;
    report.update(parametersJson(basis.parameters()));
    if (!written.empty()) report["outputs"] = written;
    std::cout << report.dump(2) << "\n";
  } else {
    std::cout << fmt::format("probe   {} ({} x {} texels)\n", probePath, env.width(), env.height());
    std::cout << fmt::format("basis   {} ({}, {} coefficients, {} per lookup{})\n", basis.name(),
                             colorSpaceName(basis.colorSpace()), basis.totalCoefficients(),
                             basis.coefficientsPerLookup(),
                             basis.functions(0).parameterText().empty()
                                 ? std::string()
                                 : ", " + basis.functions(0).parameterText());
    std::cout << "RMSE of irradiance/pi against the exact texel sum:\n";
    for (const IrradianceFit& fit : fits)
      std::cout << fmt::format("  {:<15} {:<10.6g} {}{}\n", fit.method, fit.rmse, fit.description,
                               fit.conditionNumber > 0 ? fmt::format(" (Gram condition {:.3g})", fit.conditionNumber)
                                                       : "");
    std::cout << fmt::format("exact reference {:.2f} s, fits {:.2f} s\n", referenceSeconds, fitSeconds);
    for (const std::string& path : written) std::cout << "wrote " << path << "\n";
  }
  return 0;
}

}  // namespace

int runEnvCommand(int argc, char** argv) {
  CLI::App app{
      "Project a lat-long environment's irradiance into a basis and report its RMSE (on E/pi) against the exact "
      "sum over all texels, as in section 4 of the Ambient Dice paper. SH bases: radiance projected by the texel "
      "sum and convolved with the clamped cosine, unclamped and clamped at 0. Other bases: least squares fits to "
      "the exact irradiance, solid-angle weighted and unweighted. With --signal radiance: fit its radiance instead "
      "and read diffuse and GGX specular from the fit, against exact integrals over the image."};
  std::string probePath, basisName, outDir, hemisphereAxis;
  double sharpness = 0.0;
  bool json = false;
  app.add_option("probe", probePath, "lat-long HDR or EXR image (+Y up, image centre towards -Z)")->required();
  app.add_option("--basis", basisName, "basis (see `baker bases`; sg-N takes any N in 1..64)")->required();
  app.add_flag("--json", json, "print the report as JSON on stdout");
  app.add_option("--out-dir", outDir,
                 "write reference, reconstruction (the first fit) and error (reconstruction - reference) of E/pi as "
                 "float EXR, and as PNG: exposure mapping the reference mean to 0.18, sRGB curve; the error PNG "
                 "shows |error| scaled so its maximum is white");
  app.add_option("--sg-sharpness", sharpness, "lobe sharpness for sg-N bases (default: measured per N)");
  app.add_option("--hemisphere-axis", hemisphereAxis, "x,y,z: the axis ad-hemi9's hemisphere is about (default 0,1,0)");
  std::string signal = "irradiance";
  app.add_option("--signal", signal,
                 "irradiance (default): the paper's irradiance fits above; radiance: fit the probe's radiance and "
                 "report diffuse and GGX specular (roughness 0.1, 0.3, 0.6, 1) read from it against the exact "
                 "integrals over the image (docs/specular/report.md)")
      ->check(CLI::IsMember({"irradiance", "radiance"}));
  bool upward = false;
  app.add_flag("--upward", upward,
               "with --signal radiance: read at upward-facing surfaces only (normal +Y), as a hemispherical basis "
               "(ad-hemi9) always is, about its axis");

  return runGuarded("baker env", app, argc, argv, [&]() {
    BasisParameters parameters;
    if (app.count("--sg-sharpness")) parameters.sharpness = sharpness;
    if (app.count("--hemisphere-axis")) parameters.hemisphereAxis = parseTriple("--hemisphere-axis", hemisphereAxis);
    const std::unique_ptr<Basis> basis = makeBasis(basisName, parameters);
    if (upward && signal != "radiance") throw InputError("--upward reads radiance fits: add --signal radiance");
    if (basis->hemisphere() && signal != "radiance")
      throw InputError(fmt::format("--basis {}: holds radiance over one hemisphere, not irradiance: add --signal radiance",
                                   basis->name()));
    if (signal == "radiance") {
      if (!outDir.empty()) throw InputError("--out-dir writes irradiance images: not with --signal radiance");
      return reportRadiance(*basis, probePath, upward, json);
    }
    return reportIrradiance(*basis, probePath, outDir, json);
  });
}

}  // namespace baker
