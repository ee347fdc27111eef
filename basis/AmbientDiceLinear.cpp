#include "basis/AmbientDiceLinear.h"

#include <algorithm>

#include "basis/BasisRegistry.h"

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

namespace {

const BasisRegistration kLinear({20, {"ad-linear"}, {},
                                 [](const std::string& name, const BasisParameters&) -> std::unique_ptr<Basis> {
                                   if (name == "ad-linear") return std::make_unique<AmbientDiceLinear>();
                                   return nullptr;
                                 }});

}  // namespace

nlohmann::json AmbientDiceLinearFunctions::describe() const {
  return {{"type", "icosahedron-linear"},
          {"barycentrics", barycentricsName(barycentrics())},
          {"per_vertex", nlohmann::json::array({"value"})},
          {"interpolation", "sum over the corners k of the triangle containing n of b_k value[vertex_k]"}};
}

}  // namespace baker
