#pragma once
#include <Eigen/Core>
#include <vector>

namespace baker {

// The sky a volume's light came from, kept in its file as a small lat-long map of world
// directions: relighting (relight/) takes this sky away through each probe's visibility before it
// adds another, and an engine that changes the sky at run time does the same
// (docs/RELIGHTING.md). A map and not SH: a sun is a few texels here, where SH of any order
// would ring across the sphere, and that ringing seen through a window is light where none falls.
//
// Texel (i, j), row 0 at the top, covers u ∈ [i/W, (i+1)/W), v ∈ [j/H, (j+1)/H) with φ = 2π(u − ½),
// θ = πv, d = (sin θ cos φ, cos θ, sin θ sin φ) in the world (the environment's rotation applied),
// and holds the mean radiance over that patch: each texel's flux is kept exactly.
struct SkyRadiance {
  static constexpr int kWidth = 128, kHeight = 64;
  int width = kWidth, height = kHeight;
  std::vector<float> rgb = std::vector<float>(std::size_t(kWidth) * kHeight * 3, 0.0f);

  Eigen::Vector3d texel(int column, int row) const {
    return Eigen::Vector3f::Map(&rgb[3 * (std::size_t(row) * width + column)]).cast<double>();
  }
};

// The lat-long texel (column, row) of `width` × `height` a unit world direction falls in.
Eigen::Vector2i skyTexelOf(const Eigen::Vector3d& direction, int width, int height);
// The solid angle of the lat-long patch u ∈ [u0, u0 + du), v ∈ [v0, v1).
double latLongSolidAngle(double du, double v0, double v1);

}  // namespace baker
