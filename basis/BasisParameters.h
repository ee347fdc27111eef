#pragma once
#include <Eigen/Core>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

namespace baker {

// What a basis name leaves open. Given to makeBasis, none means the basis's default; returned by
// Basis::parameters(), each that applies is filled in with the value the basis uses.
struct BasisParameters {
  std::optional<double> sharpness;                // λ of sg-N lobes; default: measured per N
  std::optional<Eigen::Vector3d> hemisphereAxis;  // the up of a hemispherical basis; default +Y
};

// As a volume's settings record them: "sg_sharpness" = "8", "hemisphere_axis" = "0,0,1", each
// number in its shortest form that reads back exactly.
std::map<std::string, std::string> parameterSettings(const BasisParameters& parameters);

// The parameters a volume's settings record. InputError naming "baker.setting.<key>" when one is
// not readable; a recorded sharpness of 0 (once written for "the default") reads as none.
BasisParameters parametersFromSettings(const std::map<std::string, std::string>& settings);

// For JSON reports: "sg_sharpness" a number, "hemisphere_axis" [x, y, z]; only those given.
nlohmann::json parametersJson(const BasisParameters& parameters);

}  // namespace baker
