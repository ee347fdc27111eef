#pragma once
#include <Eigen/Core>
#include <string>

#include "basis/DirectionSet.h"

namespace baker {

// A latitude–longitude radiance image read as a signal on the sphere, in the light-probe
// convention: texel centre (u, v) ∈ (0, 1)² ↦ θ = π(2u − 1), φ = πv and direction
// d = (sin φ sin θ, cos φ, −sin φ cos θ), so +Y is up and the image centre looks along −Z.
// Each texel stands for its exact patch of the sphere: Δθ · |sin(lat1) − sin(lat0)| steradians
// between the latitudes of its top and bottom edges.
class LatLongEnvironment {
 public:
  // `radiance` holds one RGB row per texel, image rows from the top: texel (row, column) is
  // row · width + column. Throws std::invalid_argument when the sizes disagree.
  LatLongEnvironment(int width, int height, Eigen::MatrixX3d radiance);

  // Reads an HDR or EXR image (anything OpenImageIO reads). InputError naming the file when it
  // is missing or unreadable, or when a texel is negative or not finite.
  static LatLongEnvironment load(const std::string& path);

  int width() const { return width_; }
  int height() const { return height_; }
  int texelCount() const { return width_ * height_; }
  const Eigen::MatrixX3d& radiance() const { return radiance_; }

  // φ of the texel centres in `row`, from 0 at +Y to π at −Y.
  double polarAngle(int row) const;
  // θ of the texel centres in `column`; columns are 2π/width apart.
  double azimuth(int column) const;
  Eigen::Vector3d direction(int row, int column) const;
  // The solid angle of each texel in `row`.
  double texelSolidAngle(int row) const;
  // Every texel centre with its solid angle as weight (they sum to 4π), in texel order.
  DirectionSet texels() const;

 private:
  int width_, height_;
  Eigen::MatrixX3d radiance_;
};

}  // namespace baker
