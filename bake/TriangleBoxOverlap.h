#pragma once
#include <Eigen/Core>
#include <Eigen/Geometry>

namespace baker {

// Whether triangle (a, b, c) and the closed box share a point: the separating-axis test over the
// box's three axes, the triangle's normal and the nine cross products of their edges (no axis
// separates them exactly when they overlap). Touching counts as overlapping.
bool triangleOverlapsBox(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                         const Eigen::AlignedBox3d& box);

}  // namespace baker
