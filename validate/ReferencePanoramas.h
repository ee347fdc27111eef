#pragma once
#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "images/RgbImage.h"

namespace baker {

// What the reference tools' reference_probe.py writes into a directory: probes.json (settings and
// per probe its glTF position and panorama file) and one lat-long radiance panorama per probe.
// The panoramas hold path-traced radiance only: no punctual light seen directly, so volumes
// compared with them are baked with `--no direct-punctual`.
struct ReferenceProbe {
  int index = 0;  // position in probes.json's "probes"
  Eigen::Vector3d position{0, 0, 0};
  std::string file;  // full path of the panorama
};

struct ReferenceSet {
  std::string directory;
  std::vector<ReferenceProbe> probes;
  nlohmann::json settings;  // probes.json's "settings" as written (bounces, spp, ...), or null
};

// Reads DIR/probes.json. InputError naming the file and the field when it is missing or malformed,
// or when a probe's panorama does not exist.
ReferenceSet readReferenceSet(const std::string& directory);

// The reference probe nearest to `position` (the first of equals). The set must not be empty.
const ReferenceProbe& nearestReferenceProbe(const ReferenceSet& set, const Eigen::Vector3d& position);

// The tools' panorama convention: pixel (i, j) of a W × H image, row 0 at the top,
// u = (i+0.5)/W, v = (j+0.5)/H, φ = 2π(u − 0.5), θ = πv, d = (sinθ cosφ, cosθ, sinθ sinφ):
// the image centre looks along +X, u = 0.75 along +Z, the top row is +Y.
Eigen::Vector3d panoramaDirection(int width, int height, int column, int row);
// The solid angle of a pixel of that row: (2π/W)(cos(πj/H) − cos(π(j+1)/H)); they sum to 4π.
double panoramaPixelSolidAngle(int width, int height, int row);

// Exact irradiance of a radiance panorama for each normal: E(n) = Σ L·max(0, n·d)·dΩ over pixels.
std::vector<Eigen::Vector3d> panoramaIrradiance(const RgbImage& radiance, const std::vector<Eigen::Vector3d>& normals);

}  // namespace baker
