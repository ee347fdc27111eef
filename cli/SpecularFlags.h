#pragma once
#include <CLI/CLI.hpp>

#include <Eigen/Core>
#include <optional>
#include <string>

namespace baker {

// `--roughness R --view x,y,z`: the GGX specular (basis/GgxLobe.h) a command reads from radiance.
struct SpecularFlags {
  std::optional<double> roughness;
  std::string viewText;

  void addTo(CLI::App& app);
};

struct SpecularRequest {
  double roughness = 0.0;  // in [0, 1]
  Eigen::Vector3d view;    // unit, from the surface towards the eye
};

// None when neither flag is given; InputError, before any file is read, when only one is, the
// roughness is outside [0, 1] or the view is zero.
std::optional<SpecularRequest> specularRequest(const SpecularFlags& flags);

}  // namespace baker
