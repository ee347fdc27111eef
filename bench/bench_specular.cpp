// Per radiance basis: what one read of a radiance volume costs, in nanoseconds per shading point,
// through the library (formats/VolumeReconstruction) and through the C++ decoder
// (decoders/baker_irradiance.h): the radiance in one direction, the irradiance from radiance, and
// GGX specular; each as a ratio to reading an irradiance volume of the same basis
// (Basis::reconstruct), measured in the same run. Also the one-time cost of the diffuse response
// and the blend table.
//
//   build/bench/bench_specular [--json]
#include <fmt/format.h>

#include <chrono>
#include <functional>
#include <iostream>
#include <nlohmann/json.hpp>
#include <random>

#include "basis/BasisRegistry.h"
#include "basis/DiffuseResponse.h"
#include "basis/SpecularBlend.h"
#include "cli/CommandLine.h"
#include "decoders/baker_irradiance.h"
#include "formats/ReconstructionData.h"
#include "formats/VolumeReconstruction.h"

using namespace baker;

namespace {

double seconds(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

struct Point {
  Eigen::Vector3d normal, view;
  double roughness;
};

// Best of several passes over the points, in ns per point; `read` returns something to keep.
double nsPerPoint(const std::vector<Point>& points, const std::function<float(const Point&)>& read) {
  double best = 1e30;
  volatile float sink = 0.0f;
  for (int pass = 0; pass < 5; ++pass) {
    const auto start = std::chrono::steady_clock::now();
    float sum = 0.0f;
    for (const Point& p : points) sum += read(p);
    sink = sink + sum;
    best = std::min(best, seconds(start) * 1e9 / double(points.size()));
  }
  return best;
}

baker_decode::Vec3 toDecoder(const Eigen::Vector3d& d) { return {d.x(), d.y(), d.z()}; }

// The header's decoder and table as an importer fills them from the file.
struct Decoder {
  baker_decode::BasisDecoder basis;
  baker_decode::SpecularTable table;
};

Decoder decoderFor(const Basis& basis) {
  const nlohmann::json set = reconstructionData(basis, StoredSignal::Radiance)["function_sets"][0];
  const bool lobes = set["type"] == "spherical-gaussians";
  Decoder d{baker_decode::BasisDecoder(basis.name().c_str(), lobes ? set["sharpness"].get<double>() : 0.0), {}};
  if (lobes) {
    std::vector<double> axes;
    for (const nlohmann::json& a : set["axes"])
      for (int k = 0; k < 3; ++k) axes.push_back(a[k].get<double>());
    d.basis.setLobeAxes(axes.data());
    const std::vector<double> series = set["diffuse_response"]["coefficients"].get<std::vector<double>>();
    d.basis.setDiffuseResponse(series.data(), int(series.size()));
  }
  const nlohmann::json blend = specularBlendOf(basis)->describe();
  for (int j = 0; j < baker_decode::SpecularTable::kSteps; ++j)
    for (int k = 0; k < baker_decode::SpecularTable::kSteps; ++k) {
      d.table.diffuseWeight[j][k] = blend["diffuse_weight"][j][k].get<double>();
      d.table.albedo[j][k] = blend["albedo"][j][k].get<double>();
    }
  return d;
}

}  // namespace

int main(int argc, char** argv) {
  bool json = false;
  CLI::App app{"Per radiance basis: ns per read of radiance, irradiance and GGX specular (library and C++ decoder), "
               "against an irradiance volume's read."};
  app.add_flag("--json", json, "print the results as JSON");
  return runGuarded("bench_specular", app, argc, argv, [&] {
    std::mt19937 rng(42);
    std::normal_distribution<double> normal;
    std::uniform_real_distribution<double> uniform;
    std::vector<Point> points(100000);
    for (Point& p : points)
      p = {Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized(),
           Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized(), uniform(rng)};
    nlohmann::json rows = nlohmann::json::array();
    if (!json)
      std::cout << fmt::format("{:<13} {:>7} | {:>9} {:>9} {:>9} {:>9} | {:>9} {:>9} | {:>9} {:>9}\n", "basis", "irr. ns",
                               "L(d) ns", "E(n) ns", "spec. ns", "spec/irr", "hdr E ns", "hdr spec", "resp. ms",
                               "table ms");
    for (const std::string name : {"sh-l2", "sh-l4", "ambient-cube", "ad-srbf", "ad-hemi9", "sg-12"}) {
      const auto basis = makeBasis(name);
      std::vector<float> c(std::size_t(basis->totalCoefficients()));
      for (float& x : c) x = float(uniform(rng));
      auto start = std::chrono::steady_clock::now();
      diffuseResponseOf(*basis, 0);
      const double responseMs = seconds(start) * 1e3;
      start = std::chrono::steady_clock::now();
      specularBlendOf(*basis);
      const double tableMs = seconds(start) * 1e3;
      const VolumeReconstruction library(makeBasis(name), StoredSignal::Radiance);
      const Decoder decoder = decoderFor(*basis);
      const double irradianceVolume = nsPerPoint(points, [&](const Point& p) { return basis->reconstruct(c.data(), p.normal).x(); });
      const double radiance = nsPerPoint(points, [&](const Point& p) { return library.radiance(c.data(), p.view).x(); });
      const double diffuse = nsPerPoint(points, [&](const Point& p) { return library.irradiance(c.data(), p.normal).x(); });
      const double specular = nsPerPoint(
          points, [&](const Point& p) { return library.specular(c.data(), p.normal, p.view, p.roughness).value.x(); });
      const double headerDiffuse = nsPerPoint(
          points, [&](const Point& p) { return float(decoder.basis.irradianceFromRadiance(c.data(), toDecoder(p.normal)).r); });
      const double headerSpecular = nsPerPoint(points, [&](const Point& p) {
        return float(decoder.basis.specular(c.data(), toDecoder(p.normal), toDecoder(p.view), p.roughness, decoder.table).value.r);
      });
      rows.push_back({{"basis", name},
                      {"irradiance_volume_read_ns", irradianceVolume},
                      {"library", {{"radiance_ns", radiance}, {"irradiance_ns", diffuse}, {"specular_ns", specular}}},
                      {"decoder_header", {{"irradiance_ns", headerDiffuse}, {"specular_ns", headerSpecular}}},
                      {"specular_over_irradiance_volume_read", specular / irradianceVolume},
                      {"diffuse_response_build_ms", responseMs},
                      {"blend_table_build_ms", tableMs}});
      if (!json)
        std::cout << fmt::format("{:<13} {:>7.1f} | {:>9.1f} {:>9.1f} {:>9.1f} {:>9.2f} | {:>9.1f} {:>9.1f} | {:>9.1f} {:>9.0f}\n",
                                 name, irradianceVolume, radiance, diffuse, specular, specular / irradianceVolume,
                                 headerDiffuse, headerSpecular, responseMs, tableMs);
    }
    if (json) std::cout << nlohmann::json{{"bases", rows}}.dump(2) << "\n";
    return 0;
  });
}
