#include "bake/AmbientDiceLinear.h"

#include <algorithm>

namespace baker {

void AmbientDiceLinearFunctions::evaluate(const Eigen::Vector3d& d, double* values) const {
  std::fill(values, values + count(), 0.0);
  const TrianglePoint p = Icosahedron::instance().locate(d);
  for (int k = 0; k < 3; ++k) values[p.vertices[k]] = p.barycentrics(kind_)[k];
}

Eigen::Vector3f AmbientDiceLinear::reconstruct(const float* coefficients, const Eigen::Vector3d& d) const {
  const TrianglePoint p = Icosahedron::instance().locate(d);
  Eigen::Vector3f rgb;
  for (int c = 0; c < 3; ++c) {
    const float* channel = coefficients + c * Icosahedron::kVertexCount;
    double sum = 0.0;
    for (int k = 0; k < 3; ++k) sum += p.flat[k] * channel[p.vertices[k]];
    rgb[c] = float(sum);
  }
  return rgb;
}

}  // namespace baker
