#include "formats/CellCentredBox.h"

#include <fmt/format.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "common/Error.h"
#include "formats/VolumeHeader.h"

namespace baker {

CellCentredBox cellCentredBox(const ProbeGrid& g) {
  CellCentredBox box;
  box.resolution = g.dims;
  box.size = g.spacing * g.dims.cast<double>();
  box.centre = g.origin + 0.5 * g.spacing * (g.dims.cast<double>() - Eigen::Vector3d::Ones());
  return box;
}

ProbeGrid probeGridOf(const CellCentredBox& box, const std::string& where) {
  const Eigen::Vector3i& r = box.resolution;
  if (r.minCoeff() <= 0 || r.cast<double>().prod() > kMaxProbesRead)
    throw InputError(fmt::format("{}: resolution ({}, {}, {}) is not a valid grid size", where, r.x(), r.y(), r.z()));
  const Eigen::Vector3d cell = box.size.cwiseQuotient(r.cast<double>());
  if (!cell.allFinite() || !box.centre.allFinite() || !(cell.minCoeff() > 0.0))
    throw InputError(fmt::format("{}: the box's size and centre must be finite and its size positive", where));
  if (std::abs(cell.maxCoeff() - cell.minCoeff()) > 1e-6 * cell.maxCoeff())
    throw InputError(fmt::format("{}: cells of {} × {} × {}: baker volumes have cubic cells", where, cell.x(), cell.y(),
                                 cell.z()));
  ProbeGrid g;
  g.dims = r;
  g.spacing = cell.x();
  g.origin = box.centre - 0.5 * box.size + 0.5 * cell;
  return g;
}

Eigen::Vector3d jsonVector3(const nlohmann::json& value, const std::string& where, const std::string& field) {
  const auto v = value.get<std::vector<double>>();
  if (v.size() != 3) throw InputError(fmt::format("{}: \"{}\" needs three numbers", where, field));
  return {v[0], v[1], v[2]};
}

Eigen::Vector3i jsonResolution(const nlohmann::json& value, const std::string& where, const std::string& field) {
  // Read as numbers and checked before any conversion: a JSON number out of int's range must be
  // refused, not converted.
  const auto v = value.get<std::vector<double>>();
  if (v.size() != 3) throw InputError(fmt::format("{}: \"{}\" needs three whole numbers", where, field));
  for (double n : v)
    if (!(n >= 1.0 && n <= kMaxProbesRead && n == std::floor(n)))
      throw InputError(fmt::format("{}: \"{}\" holds {}; expected whole numbers from 1 to 2^28", where, field, n));
  return {int(v[0]), int(v[1]), int(v[2])};
}

}  // namespace baker
