#pragma once
#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "scene/PiecewiseConstant.h"

namespace baker {

// Rec. 709 luminance: the weight environment sampling follows.
inline float luminance(const Eigen::Vector3f& rgb) { return 0.2126f * rgb.x() + 0.7152f * rgb.y() + 0.0722f * rgb.z(); }

// The radiance arriving from infinitely far away: nothing, a constant sky, or a lat-long map.
//
// Map convention (that of ../shared/tools/README.md, so that references line up): glTF world,
// +Y up; texel (i, j), row 0 at the top, covers u ∈ [i/W, (i+1)/W), v ∈ [j/H, (j+1)/H) with
// φ = 2π(u − ½), θ = πv and d = (sinθ cosφ, cosθ, sinθ sinφ): the image centre looks along +X,
// u = ¾ along +Z. The map is piecewise constant (each texel's radiance over its whole patch of
// the sphere), which is exactly what the sampling tables below assume, so lookups and sampling
// agree and Σ texel × solid angle is the exact integral. A rotation of +α turns the map about +Y
// by the right-hand rule (what was seen along +Z is then seen along +X for α = 90°).
class Environment {
 public:
  enum class Kind { None, Constant, Map };

  Environment() = default;
  static Environment constant(const Eigen::Vector3f& radiance);
  // `rgb`: W·H texels row by row from the top, 3 floats each. Negative or non-finite texels
  // become 0 and are counted in sanitizedTexels(); InputError naming `source` when a texel times
  // `intensity` leaves single precision.
  static Environment latLong(int width, int height, std::vector<float> rgb, float intensity, float rotationDegrees,
                             std::string source);

  Kind kind() const { return kind_; }
  const std::string& source() const { return source_; }
  int width() const { return width_; }
  int height() const { return height_; }
  float intensity() const { return intensity_; }
  float rotationDegrees() const { return rotationDegrees_; }
  const Eigen::Vector3f& constantRadiance() const { return constant_; }
  std::size_t sanitizedTexels() const { return sanitized_; }
  // One line for people: "none", "constant sky r,g,b", or "map FILE (W × H, intensity x, rotated y°)".
  std::string describe() const;
  // Whether any direction brings light (a black map or sky brings none and needs no sampling).
  bool emits() const { return kind_ == Kind::Map ? table_ != nullptr : luminance(constant_) > 0.0f; }

  // The radiance seen looking along the unit world vector `direction` (a ray escaping along it).
  Eigen::Vector3f radiance(const Eigen::Vector3f& direction) const;

  struct Sample {
    Eigen::Vector3f direction{0.0f, 1.0f, 0.0f};
    Eigen::Vector3f radiance{0.0f, 0.0f, 0.0f};
    float pdf = 0.0f;  // per steradian; 0 when there is nothing to sample
  };
  // A direction with probability density proportional to the luminance of the radiance seen
  // along it (a map) or uniform on the sphere (a constant sky), from two uniform numbers in [0, 1).
  Sample sample(float xi1, float xi2) const;
  // The density sample() draws `direction` with.
  float pdf(const Eigen::Vector3f& direction) const;

  // The lat-long texel that `direction` looks at (after the rotation): column, row.
  Eigen::Vector2i texelOf(const Eigen::Vector3f& direction) const;
  // For sums over a map's texels (its integrals: the map is piecewise constant): the world
  // direction through texel (column, row)'s centre, the exact solid angle of a texel of that row,
  // and its radiance (× intensity).
  Eigen::Vector3d texelCentre(int column, int row) const;
  // The world direction of map coordinates (u, v) ∈ [0, 1]², after the rotation.
  Eigen::Vector3d directionAt(double u, double v) const;
  double texelSolidAngle(int row) const;
  Eigen::Vector3f texelRadiance(int column, int row) const {
    return Eigen::Vector3f::Map(&rgb_[3 * (std::size_t(row) * width_ + column)]);
  }

 private:
  Eigen::Vector3f toMap(const Eigen::Vector3f& world) const;
  Eigen::Vector3f toWorld(const Eigen::Vector3f& map) const;

  Kind kind_ = Kind::None;
  std::string source_;
  Eigen::Vector3f constant_{0.0f, 0.0f, 0.0f};
  int width_ = 0;
  int height_ = 0;
  float intensity_ = 1.0f;
  float rotationDegrees_ = 0.0f;
  float cosRotation_ = 1.0f;
  float sinRotation_ = 0.0f;
  std::vector<float> rgb_;  // texels × intensity
  std::size_t sanitized_ = 0;
  // Cells weighted by luminance × exact solid angle; shared so a Scene stays cheap to move.
  std::shared_ptr<const PiecewiseConstant2D> table_;
  double luminanceIntegral_ = 0.0;  // Σ luminance × solid angle over the sphere
};

}  // namespace baker
