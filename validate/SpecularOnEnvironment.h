#pragma once
#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "basis/Basis.h"
#include "validate/LatLongEnvironment.h"
#include "validate/SignalFit.h"

namespace baker {

// What a radiance volume would give under a distant light probe: the probe's radiance fitted in a
// basis (as `baker bases --signal radiance` fits it, at that command's resolution), then read as
// diffuse irradiance and as GGX specular (formats/VolumeReconstruction), against the exact
// integrals over the full-resolution image's texels. `baker env --signal radiance`; the light
// probe half of docs/specular/report.md.

// The surfaces it is read at: 16 normals spread over the sphere, each seen from three views at
// n·v = 1, 0.7 and 0.3, turned about the normal by the golden angle from one normal to the next.
struct SpecularFrame {
  Eigen::Vector3d normal, view;
};
std::vector<SpecularFrame> specularFrames();
// Surfaces facing `up` only, for bases that hold one hemisphere (Basis::hemisphere): n = up, seen
// at the same three n·v from 8 directions around it.
std::vector<SpecularFrame> upwardFrames(const Eigen::Vector3d& up);

// The exact references, over the image as a piecewise-constant function of direction: the
// irradiance at a unit normal, summed over every texel; the GGX-weighted mean radiance S, summed
// over the texels for a lobe at least 8 texels wide (α ≥ 8 · 2π/width) and otherwise by GgxLobe's
// quadrature (64 × 128 half vectors, each reading the texel it falls in).
Eigen::Vector3d exactIrradianceAt(const LatLongEnvironment& image, const Eigen::Vector3d& normal);
Eigen::Vector3d exactSpecularAt(const LatLongEnvironment& image, const SpecularFrame& frame, double roughness);

struct EnvironmentSpecularScore {
  FitMethod fit = FitMethod::Linear;
  int bytesPerProbe = 0;
  // Relative RMSE: the RMSE over frames and RGB channels divided by the reference's mean.
  double diffuseRelativeRmse = 0.0;              // E(n), at each frame's normal
  std::vector<std::optional<double>> specularRelativeRmse;  // S, per roughness; none where S is 0 at every pair
};

// One score per fit that applies to the basis (linear, then non-negative). InputError naming
// `path` when the image's size is not a multiple of the fit's resolution or no light reaches the
// frames' normals; NumericalError when the
// texels cannot resolve the basis's functions; std::invalid_argument for a roughness outside [0, 1].
std::vector<EnvironmentSpecularScore> scoreSpecularOnEnvironment(const Basis& basis, const LatLongEnvironment& image,
                                                                 const std::string& path, const std::vector<double>& roughness,
                                                                 const std::vector<SpecularFrame>& frames);

}  // namespace baker
