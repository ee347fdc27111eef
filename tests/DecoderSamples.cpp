// decoder_samples: irradiance and visibility that decoders/baker_irradiance.h decodes from random
// coefficients at chosen directions, for every basis, as JSON on stdout: what the ports of the
// header to other languages (decoders/baker_irradiance.js) are checked against.
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>
#include <random>
#include <string>
#include <vector>

#include "basis/BasisRegistry.h"
#include "decoders/baker_irradiance.h"
#include "formats/ReconstructionData.h"

namespace {

using nlohmann::json;

constexpr unsigned kSeed = 77;
constexpr int kDirections = 60;

std::vector<std::vector<double>> directions(std::mt19937& rng) {
  std::vector<std::vector<double>> out;
  // The icosahedron's vertices and the axes first: where triangle and octant lookups are at their edges.
  for (int i = 0; i < 12; ++i) {
    const baker_decode::Vec3 v = baker_decode::icosahedronVertex(i);
    out.push_back({v.x, v.y, v.z});
  }
  for (int a = 0; a < 3; ++a)
    for (double s : {1.0, -1.0}) {
      std::vector<double> d(3, 0.0);
      d[a] = s;
      out.push_back(d);
    }
  std::normal_distribution<double> gaussian;
  while (int(out.size()) < kDirections) {
    const baker_decode::Vec3 d = baker_decode::normalize({gaussian(rng), gaussian(rng), gaussian(rng)});
    out.push_back({d.x, d.y, d.z});
  }
  return out;
}

json samplesOf(const std::string& name, std::mt19937& rng) {
  const auto basis = baker::makeBasis(name);
  const json set = baker::reconstructionData(*basis)["function_sets"][0];
  double sharpness = 0.0;
  std::vector<double> axes;
  json entry = {{"basis", name}};
  if (set["type"] == "spherical-gaussians") {
    sharpness = set["sharpness"].get<double>();
    for (const json& axis : set["axes"])
      for (int k = 0; k < 3; ++k) axes.push_back(axis[k].get<double>());
    entry["sharpness"] = sharpness;
    entry["axes"] = set["axes"];
  }
  baker_decode::BasisDecoder decoder(name.c_str(), sharpness);
  if (!axes.empty()) decoder.setLobeAxes(axes.data());
  std::uniform_real_distribution<float> uniform(-1.0f, 1.0f);
  json cases = json::array();
  for (const std::vector<double>& d : directions(rng)) {
    std::vector<float> c(decoder.coefficientsPerProbe());
    for (float& x : c) x = uniform(rng);
    const baker_decode::Rgb e = decoder.irradiance(c.data(), {d[0], d[1], d[2]});
    cases.push_back({{"coefficients", c},
                     {"direction", d},
                     {"irradiance", {e.r, e.g, e.b}},
                     {"visibility", decoder.visibility(c.data(), {d[0], d[1], d[2]})}});
  }
  entry["coefficients_per_probe"] = decoder.coefficientsPerProbe();
  entry["cases"] = cases;
  return entry;
}

}  // namespace

int main() {
  std::mt19937 rng(kSeed);
  json all = json::array();
  for (const std::string& name : baker::basisNames()) all.push_back(samplesOf(name, rng));
  std::cout << all.dump() << "\n";
  return 0;
}
