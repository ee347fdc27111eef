#include "validate/ReferencePanoramas.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "common/Error.h"

namespace baker {

ReferenceSet readReferenceSet(const std::string& directory) {
  const std::filesystem::path manifest = std::filesystem::path(directory) / "probes.json";
  const std::string name = manifest.string();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(manifest, ec))
    throw InputError(fmt::format("{}: no such file (expected the output directory of reference_probe.py)", name));
  std::ifstream in(manifest);
  const nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
  if (j.is_discarded() || !j.is_object()) throw InputError(fmt::format("{}: not a JSON object", name));
  const auto probes = j.find("probes");
  if (probes == j.end() || !probes->is_array() || probes->empty())
    throw InputError(fmt::format("{}: \"probes\" must be a non-empty array", name));

  ReferenceSet set;
  set.directory = directory;
  const auto settings = j.find("settings");
  if (settings != j.end()) set.settings = *settings;
  for (std::size_t k = 0; k < probes->size(); ++k) {
    const nlohmann::json& p = (*probes)[k];
    const std::string where = fmt::format("{}: probes[{}]", name, k);
    const auto position = p.is_object() ? p.find("position_gltf") : p.end();
    if (position == p.end() || !position->is_array() || position->size() != 3 ||
        !std::all_of(position->begin(), position->end(), [](const nlohmann::json& v) { return v.is_number(); }))
      throw InputError(fmt::format("{}.position_gltf: expected three numbers", where));
    const auto file = p.find("file");
    if (file == p.end() || !file->is_string()) throw InputError(fmt::format("{}.file: expected a file name", where));
    ReferenceProbe probe;
    probe.index = int(k);
    probe.position = Eigen::Vector3d((*position)[0].get<double>(), (*position)[1].get<double>(),
                                     (*position)[2].get<double>());
    if (!probe.position.allFinite()) throw InputError(fmt::format("{}.position_gltf: not finite", where));
    probe.file = (std::filesystem::path(directory) / file->get<std::string>()).string();
    if (!std::filesystem::is_regular_file(probe.file, ec))
      throw InputError(fmt::format("{}.file: {} does not exist", where, probe.file));
    set.probes.push_back(probe);
  }
  return set;
}

const ReferenceProbe& nearestReferenceProbe(const ReferenceSet& set, const Eigen::Vector3d& position) {
  const ReferenceProbe* nearest = &set.probes.front();
  for (const ReferenceProbe& p : set.probes)
    if ((p.position - position).squaredNorm() < (nearest->position - position).squaredNorm()) nearest = &p;
  return *nearest;
}

Eigen::Vector3d panoramaDirection(int width, int height, int column, int row) {
  const double u = (column + 0.5) / width, v = (row + 0.5) / height;
  const double phi = 2.0 * M_PI * (u - 0.5), theta = M_PI * v;
  return {std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi)};
}

double panoramaPixelSolidAngle(int width, int height, int row) {
  return (2.0 * M_PI / width) * (std::cos(M_PI * row / height) - std::cos(M_PI * (row + 1) / height));
}

std::vector<Eigen::Vector3d> panoramaIrradiance(const RgbImage& radiance, const std::vector<Eigen::Vector3d>& normals) {
  std::vector<Eigen::Vector3d> e(normals.size(), Eigen::Vector3d::Zero());
  for (int row = 0; row < radiance.height; ++row) {
    const double solidAngle = panoramaPixelSolidAngle(radiance.width, radiance.height, row);
    for (int column = 0; column < radiance.width; ++column) {
      const Eigen::Vector3d d = panoramaDirection(radiance.width, radiance.height, column, row);
      const float* l = radiance.pixel(row, column);
      const Eigen::Vector3d weighted = solidAngle * Eigen::Vector3d(l[0], l[1], l[2]);
      for (std::size_t n = 0; n < normals.size(); ++n) e[n] += std::max(0.0, normals[n].dot(d)) * weighted;
    }
  }
  return e;
}

}  // namespace baker
