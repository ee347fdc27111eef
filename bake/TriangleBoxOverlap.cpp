#include "bake/TriangleBoxOverlap.h"

#include <algorithm>
#include <cmath>

namespace baker {

bool triangleOverlapsBox(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c,
                         const Eigen::AlignedBox3d& box) {
  const Eigen::Vector3d centre = box.center();
  const Eigen::Vector3d half = 0.5 * box.sizes();
  // In the box's frame the box is [-half, half]: a separating axis is one along which the
  // triangle's projection and the box's projection (radius |axis|·half) do not meet.
  const Eigen::Vector3d v[3] = {a - centre, b - centre, c - centre};
  const auto separates = [&](const Eigen::Vector3d& axis) {
    if (axis.squaredNorm() == 0.0) return false;  // parallel edges: no axis
    const double p0 = axis.dot(v[0]), p1 = axis.dot(v[1]), p2 = axis.dot(v[2]);
    const double radius = half.dot(axis.cwiseAbs());
    return std::min({p0, p1, p2}) > radius || std::max({p0, p1, p2}) < -radius;
  };
  for (int axis = 0; axis < 3; ++axis)
    if (separates(Eigen::Vector3d::Unit(axis))) return false;
  const Eigen::Vector3d edges[3] = {v[1] - v[0], v[2] - v[1], v[0] - v[2]};
  if (separates(edges[0].cross(edges[1]))) return false;
  for (const Eigen::Vector3d& edge : edges)
    for (int axis = 0; axis < 3; ++axis)
      if (separates(Eigen::Vector3d::Unit(axis).cross(edge))) return false;
  return true;
}

}  // namespace baker
