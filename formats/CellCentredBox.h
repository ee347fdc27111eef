#pragma once
#include <Eigen/Core>
#include <nlohmann/json_fwd.hpp>
#include <string>

#include "volume/ProbeGrid.h"

namespace baker {

// A box cut into resolution cells with a probe at the centre of each: how Bevy (its unit cube
// under the volume's Transform) and three.js r187 (LightProbeGrid's box) place probes.
struct CellCentredBox {
  Eigen::Vector3d centre{0, 0, 0};
  Eigen::Vector3d size{1, 1, 1};
  Eigen::Vector3i resolution{1, 1, 1};
};

// The box whose cell centres are the grid's probes.
CellCentredBox cellCentredBox(const ProbeGrid& grid);

// The grid of a box read from a file: InputError naming `where` unless the resolution is a grid
// size a reader accepts and the cells are cubes of positive size (baker's grids have one spacing).
ProbeGrid probeGridOf(const CellCentredBox& box, const std::string& where);

// Three numbers of a JSON file's field, or InputError naming `where` and `field`.
Eigen::Vector3d jsonVector3(const nlohmann::json& value, const std::string& where, const std::string& field);
Eigen::Vector3i jsonResolution(const nlohmann::json& value, const std::string& where, const std::string& field);

}  // namespace baker
