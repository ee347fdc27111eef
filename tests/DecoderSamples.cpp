// decoder_samples: irradiance and visibility that decoders/baker_irradiance.h decodes from random
// coefficients at chosen directions, for every basis, as JSON on stdout: what the ports of the
// header to other languages (decoders/baker_irradiance.js) are checked against.
// `decoder_samples adaptive`: an adaptive volume of random probes instead (three levels, each
// holding some of its bricks) and what the header samples at points in and around it.
// `decoder_samples radiance`: per basis, radiance volumes' coefficients and what the library
// (formats/VolumeReconstruction) reads from them: radiance, irradiance, visibility, specular.
// `decoder_samples leak`: random distance maps, probes, points and normals, and the header's
// leak-aware weight (leakWeight) for each.
// `decoder_samples relit`: per basis, an irradiance volume's light less its sky_direct, its
// visibility and a sky's SH, and the irradiance the library relights at run time from them.
#include <algorithm>
#include <array>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>
#include <random>
#include <string>
#include <vector>

#include "basis/BasisRegistry.h"
#include "basis/SpecularBlend.h"
#include "decoders/baker_irradiance.h"
#include "formats/ReconstructionData.h"
#include "formats/VolumeReconstruction.h"

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
  const json set = baker::reconstructionData(*basis, baker::StoredSignal::Irradiance)["function_sets"][0];
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

json vec(const Eigen::Vector3f& v) { return {v.x(), v.y(), v.z()}; }

// What a radiance volume's reader needs of its metadata, and the library's readings of random
// probes at random normals, views and roughness (the specular table only for bases it decodes).
json radianceSamplesOf(std::unique_ptr<baker::Basis> basis, std::mt19937& rng) {
  const baker::VolumeReconstruction library(std::move(basis), baker::StoredSignal::Radiance);
  const json set = baker::reconstructionData(library.basis(), baker::StoredSignal::Radiance)["function_sets"][0];
  json entry = {{"basis", library.basis().name()}, {"diffuse_response", set["diffuse_response"]}};
  if (set["type"] == "spherical-gaussians") entry["sharpness"] = set["sharpness"];
  if (set.contains("axes")) entry["axes"] = set["axes"];
  if (set["diffuse_response"].is_null()) return entry;
  const json blend = baker::specularBlendOf(library.basis())->describe();
  entry["specular"] = {{"diffuse_weight", blend["diffuse_weight"]}, {"albedo", blend["albedo"]}};
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  std::normal_distribution<double> gaussian;
  const auto direction = [&] { return Eigen::Vector3d(gaussian(rng), gaussian(rng), gaussian(rng)).normalized(); };
  json cases = json::array();
  for (int n = 0; n < 40; ++n) {
    std::vector<float> c(std::size_t(library.basis().totalCoefficients()));
    for (float& x : c) x = uniform(rng);
    const Eigen::Vector3d normal = direction(), view = n == 0 ? normal : direction();
    const double roughness = n % 5 == 0 ? double(n % 2) : uniform(rng);
    const baker::VolumeReconstruction::Specular s = library.specular(c.data(), normal, view, roughness);
    cases.push_back({{"coefficients", c},
                     {"normal", {normal.x(), normal.y(), normal.z()}},
                     {"view", {view.x(), view.y(), view.z()}},
                     {"roughness", roughness},
                     {"radiance", vec(library.radiance(c.data(), normal))},
                     {"irradiance", vec(library.irradiance(c.data(), normal))},
                     {"visibility", library.skyVisibility(c.data(), normal)},
                     {"specular", {{"value", vec(s.value)}, {"albedo", s.albedo}, {"diffuse_weight", s.diffuseWeight}}}});
  }
  entry["cases"] = cases;
  return entry;
}

// Random "rest" coefficients, visibility and sky SH (27 numbers: R's nine, G's, B's), and the
// library's run-time relit irradiance (VolumeReconstruction::relitIrradiance) at random normals.
json relitSamplesOf(const std::string& name, std::mt19937& rng) {
  const baker::VolumeReconstruction library(baker::makeBasis(name), baker::StoredSignal::Irradiance);
  const json set = baker::reconstructionData(library.basis(), baker::StoredSignal::Irradiance)["function_sets"][0];
  json entry = {{"basis", name}};
  if (set["type"] == "spherical-gaussians") entry["sharpness"] = set["sharpness"];
  if (set.contains("axes")) entry["axes"] = set["axes"];
  std::uniform_real_distribution<float> uniform(-1.0f, 1.0f);
  std::normal_distribution<double> gaussian;
  json cases = json::array();
  for (int n = 0; n < 30; ++n) {
    std::vector<float> rest(std::size_t(library.basis().totalCoefficients())),
        visibility(std::size_t(library.basis().functions(0).count())), sky(27);
    for (std::vector<float>* values : {&rest, &visibility, &sky})
      for (float& x : *values) x = uniform(rng);
    baker::SkyHarmonics harmonics;
    for (int k = 0; k < 9; ++k)
      for (int c = 0; c < 3; ++c) harmonics.radiance(k, c) = sky[std::size_t(9 * c + k)];
    const Eigen::Vector3d normal = Eigen::Vector3d(gaussian(rng), gaussian(rng), gaussian(rng)).normalized();
    cases.push_back({{"rest", rest},
                     {"visibility", visibility},
                     {"sky", sky},
                     {"normal", {normal.x(), normal.y(), normal.z()}},
                     {"irradiance", vec(library.relitIrradiance(rest.data(), visibility.data(), normal, harmonics))}});
  }
  entry["cases"] = cases;
  return entry;
}

// Maps whose texels are open (moments 1) with probability 0.3 and otherwise hold a mean distance
// and a mean square at least its square; points within two spacings of the probe.
json leakSamples(std::mt19937& rng) {
  std::uniform_real_distribution<double> uniform(0.0, 1.0), around(-2.0, 2.0);
  std::normal_distribution<double> gaussian;
  json cases = json::array();
  for (int n = 0; n < 400; ++n) {
    const baker_decode::DistanceMap map{n % 2 == 0 ? 8 : 4, 2.5};
    std::vector<float> moments;
    for (int t = 0; t < map.size * map.size; ++t) {
      const double mean = uniform(rng) < 0.3 ? 1.0 : uniform(rng);
      moments.push_back(float(mean));
      moments.push_back(float(std::min(1.0, mean * mean + 0.05 * uniform(rng))));
    }
    const baker_decode::Vec3 probe{around(rng), around(rng), around(rng)};
    const baker_decode::Vec3 point{probe.x + around(rng), probe.y + around(rng), probe.z + around(rng)};
    const baker_decode::Vec3 normal = baker_decode::normalize({gaussian(rng), gaussian(rng), gaussian(rng)});
    cases.push_back({{"map", {{"size", map.size}, {"cap", map.cap}}},
                     {"moments", moments},
                     {"probe", {probe.x, probe.y, probe.z}},
                     {"point", {point.x, point.y, point.z}},
                     {"normal", {normal.x, normal.y, normal.z}},
                     {"weight", baker_decode::leakWeight(map, moments.data(), probe, point, normal, 1.0)}});
  }
  return cases;
}

// Three levels, spacing ÷3 per level, each holding some bricks, the coarsest not all of them. Per held brick
// 8³ probes of random numbers, as a pool slot holds them (probes past the grid's edge included).
struct AdaptiveLevel {
  baker_decode::Level level;
  std::vector<int> bricks;  // held, increasing
  std::vector<int> masks;   // of each held brick, its sub-bricks held
  std::vector<unsigned char> held;
  std::vector<float> coefficients, visibility;  // per slot, per probe of the brick
};

AdaptiveLevel adaptiveLevel(baker_decode::Vec3 origin, double spacing, std::array<int, 3> dims, double heldShare,
                            const baker_decode::BasisDecoder& decoder, std::mt19937& rng) {
  AdaptiveLevel out;
  out.level = {origin, spacing, {dims[0], dims[1], dims[2]}, nullptr};
  const int brickCount = ((dims[0] + 7) / 8) * ((dims[1] + 7) / 8) * ((dims[2] + 7) / 8);
  std::bernoulli_distribution keep(heldShare);
  out.held.assign(brickCount, 0);
  // No level holds its last column of bricks along x: points there read level 0's held probes
  // renormalised, or none.
  // Half the held bricks hold only some of their sub-bricks of 4³.
  const int bricksX = (dims[0] + 7) / 8;
  std::bernoulli_distribution whole(0.5);
  std::uniform_int_distribution<int> someSubBricks(1, 254);
  for (int b = 0; b < brickCount; ++b)
    if (b == 0 || (b % bricksX != bricksX - 1 && keep(rng))) {
      const int mask = b == 0 || whole(rng) ? 0xFF : someSubBricks(rng);
      out.held[b] = (unsigned char)mask;
      out.bricks.push_back(b);
      out.masks.push_back(mask);
    }
  out.level.subBricksHeld = out.held.data();
  std::uniform_real_distribution<float> uniform(-1.0f, 1.0f);
  out.coefficients.resize(out.bricks.size() * 512 * decoder.coefficientsPerProbe());
  out.visibility.resize(out.bricks.size() * 512 * decoder.coefficientCount(0));
  for (float& x : out.coefficients) x = uniform(rng);
  for (float& x : out.visibility) x = uniform(rng);
  return out;
}

// Where level probe `probe` sits in the level's slots (its rank among held bricks, then its place in
// the brick), or -1 when the level does not hold it.
long long slotProbe(const AdaptiveLevel& l, long long probe) {
  const long long nx = l.level.dims[0], ny = l.level.dims[1];
  const long long i = probe % nx, j = (probe / nx) % ny, k = probe / (nx * ny);
  const long long brick = i / 8 + (nx + 7) / 8 * (j / 8 + (ny + 7) / 8 * (k / 8));
  const auto at = std::lower_bound(l.bricks.begin(), l.bricks.end(), brick);
  if (at == l.bricks.end() || *at != brick) return -1;
  const int subBrick = int((i / 4) % 2 + 2 * ((j / 4) % 2) + 4 * ((k / 4) % 2));
  if (!(l.masks[std::size_t(at - l.bricks.begin())] >> subBrick & 1)) return -1;
  return (at - l.bricks.begin()) * 512 + i % 8 + 8 * (j % 8 + 8 * (k % 8));
}

json adaptiveSamples(const std::string& name, std::mt19937& rng) {
  baker_decode::BasisDecoder decoder(name.c_str(), 0.0);
  const int perProbe = decoder.coefficientsPerProbe(), visibilityCount = decoder.coefficientCount(0);
  // Origin, spacings and positions exactly representable in float: what a GPU decoder is given
  // then matches what the header is given, and only their arithmetic differs.
  const baker_decode::Vec3 origin{-0.25, 0.125, -0.125};
  std::vector<AdaptiveLevel> levels;
  levels.push_back(adaptiveLevel(origin, 2.25, {10, 4, 3}, 0.0, decoder, rng));
  levels.push_back(adaptiveLevel(origin, 0.75, {28, 10, 7}, 0.5, decoder, rng));
  levels.push_back(adaptiveLevel(origin, 0.25, {82, 28, 19}, 0.15, decoder, rng));
  std::vector<baker_decode::Level> headerLevels;
  json levelsJson = json::array();
  for (const AdaptiveLevel& l : levels) {
    headerLevels.push_back(l.level);
    levelsJson.push_back({{"origin", {l.level.origin.x, l.level.origin.y, l.level.origin.z}},
                          {"spacing", l.level.spacing},
                          {"dims", l.level.dims},
                          {"bricks", l.bricks},
                          {"masks", l.masks},
                          {"coefficients", l.coefficients},
                          {"visibility", l.visibility}});
  }
  std::uniform_real_distribution<double> along(-0.1, 1.1);
  std::normal_distribution<double> gaussian;
  const std::vector<float> none(perProbe, 0.0f);
  json points = json::array();
  for (int p = 0; p < 600; ++p) {
    const baker_decode::Vec3 at{float(origin.x + 9 * 2.25 * along(rng)), float(origin.y + 3 * 2.25 * along(rng)),
                                float(origin.z + 2 * 2.25 * along(rng))};
    const baker_decode::Vec3 n = baker_decode::normalize({gaussian(rng), gaussian(rng), gaussian(rng)});
    const baker_decode::LevelNeighbourhood picked = baker_decode::finestLevelNeighbourhood(at, headerLevels.data(), 3);
    const AdaptiveLevel& l = levels[picked.level];
    const float *values[8], *visibility[8];
    for (int c = 0; c < 8; ++c) {
      const long long s = slotProbe(l, picked.around.probe[c]);
      values[c] = s < 0 ? none.data() : &l.coefficients[s * perProbe];
      visibility[c] = s < 0 ? none.data() : &l.visibility[s * visibilityCount];
    }
    std::vector<float> blended(perProbe), blendedVisibility(visibilityCount);
    baker_decode::blendProbes(values, picked.around.weight, perProbe, blended.data());
    baker_decode::blendProbes(visibility, picked.around.weight, visibilityCount, blendedVisibility.data());
    const baker_decode::Rgb e = decoder.irradiance(blended.data(), n);
    points.push_back({{"position", {at.x, at.y, at.z}},
                      {"normal", {n.x, n.y, n.z}},
                      {"level", picked.level},
                      {"weights", picked.around.weight},
                      {"irradiance", {e.r, e.g, e.b}},
                      {"visibility", decoder.visibility(blendedVisibility.data(), n)}});
  }
  return {{"basis", name}, {"levels", levelsJson}, {"points", points}};
}

}  // namespace

int main(int argc, char** argv) {
  std::mt19937 rng(kSeed);
  if (argc > 1 && std::string(argv[1]) == "adaptive") {
    json all = json::array();
    for (const char* name : {"sh-l2", "ad-ycocg"}) all.push_back(adaptiveSamples(name, rng));
    std::cout << all.dump() << "\n";
    return 0;
  }
  if (argc > 1 && std::string(argv[1]) == "radiance") {
    json all = json::array();
    for (const std::string& name : baker::basisNames()) all.push_back(radianceSamplesOf(baker::makeBasis(name), rng));
    // Radiance only, so not listed: about +Y, where the decoders' own axes serve, and about a wall's
    // axis, where they take the file's.
    all.push_back(radianceSamplesOf(baker::makeBasis("ad-hemi9"), rng));
    all.push_back(radianceSamplesOf(baker::makeBasis("ad-hemi9", {std::nullopt, Eigen::Vector3d(0.6, 0.0, -0.8)}), rng));
    std::cout << all.dump() << "\n";
    return 0;
  }
  if (argc > 1 && std::string(argv[1]) == "leak") {
    std::cout << leakSamples(rng).dump() << "\n";
    return 0;
  }
  if (argc > 1 && std::string(argv[1]) == "relit") {
    json all = json::array();
    for (const std::string& name : baker::basisNames()) all.push_back(relitSamplesOf(name, rng));
    std::cout << all.dump() << "\n";
    return 0;
  }
  json all = json::array();
  for (const std::string& name : baker::basisNames()) all.push_back(samplesOf(name, rng));
  std::cout << all.dump() << "\n";
  return 0;
}
