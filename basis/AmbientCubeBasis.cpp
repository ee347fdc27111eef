#include "basis/AmbientCubeBasis.h"

#include "basis/BasisRegistry.h"

namespace baker {

void AmbientCubeLobes::evaluate(const Eigen::Vector3d& d, double* values) const {
  for (int axis = 0; axis < 3; ++axis) {
    const double a = d[axis];
    values[2 * axis] = a > 0.0 ? a * a : 0.0;
    values[2 * axis + 1] = a < 0.0 ? a * a : 0.0;
  }
}

std::optional<RadialLobes> AmbientCubeLobes::radialLobes() const {
  RadialLobes lobes{[](double t) { return t > 0.0 ? t * t : 0.0; }, {}};
  for (int axis = 0; axis < 3; ++axis)
    for (double sign : {1.0, -1.0}) lobes.axes.push_back(sign * Eigen::Vector3d::Unit(axis));
  return lobes;
}

Eigen::Vector3f AmbientCubeBasis::reconstruct(const float* coefficients, const Eigen::Vector3d& d) const {
  // Of each ± pair only the lobe on d's side is non-zero, and its value is d[axis]² either way.
  Eigen::Vector3f color = Eigen::Vector3f::Zero();
  for (int axis = 0; axis < 3; ++axis) {
    const int lobe = 2 * axis + (d[axis] < 0.0 ? 1 : 0);
    const float weight = float(d[axis] * d[axis]);
    for (int c = 0; c < 3; ++c) color[c] += weight * coefficients[6 * c + lobe];
  }
  return color;
}

namespace {

const BasisRegistration kAmbientCube({60, {"ambient-cube"}, {},
                                      [](const std::string& name, const BasisParameters&) -> std::unique_ptr<Basis> {
                                        if (name == "ambient-cube") return std::make_unique<AmbientCubeBasis>();
                                        return nullptr;
                                      }});

}  // namespace

nlohmann::json AmbientCubeLobes::describe() const {
  return {{"type", "cube-lobes"},
          {"axes", {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}}},
          {"lobe", "f_i(n) = max(0, axes[i].n)^2"}};
}

}  // namespace baker
