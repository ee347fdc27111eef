#include "basis/AmbientDiceSrbf.h"

#include <cmath>

#include "basis/BasisRegistry.h"
#include "basis/Icosahedron.h"

namespace baker {
namespace {

// One vertex of each antipodal pair (the other is i ^ 3: both sign bits flipped).
constexpr int kPairs[6] = {0, 1, 4, 5, 8, 9};

}  // namespace

AmbientDiceSrbfFunctions::AmbientDiceSrbfFunctions(double cos2Weight, double cos4Weight) {
  const double scale = 1.0 / (2.0 * cos2Weight + 6.0 / 5.0 * cos4Weight);  // the sums in the header
  cos2_ = scale * cos2Weight;
  cos4_ = scale * cos4Weight;
}

double AmbientDiceSrbfFunctions::lobe(double c) const {
  const double c2 = c * c;
  return c2 * (cos2_ + cos4_ * c2);
}

void AmbientDiceSrbfFunctions::evaluate(const Eigen::Vector3d& d, double* values) const {
  const Icosahedron& ico = Icosahedron::instance();
  for (int i = 0; i < count(); ++i) {
    const double c = ico.vertex(i).dot(d);
    values[i] = c > 0.0 ? lobe(c) : 0.0;
  }
}

std::vector<Eigen::Vector3d> AmbientDiceSrbfFunctions::kinkPlanes() const {
  std::vector<Eigen::Vector3d> normals;
  for (int i : kPairs) normals.push_back(Icosahedron::instance().vertex(i));
  return normals;
}

std::optional<RadialLobes> AmbientDiceSrbfFunctions::radialLobes() const {
  RadialLobes lobes{[this](double t) { return t > 0.0 ? lobe(t) : 0.0; }, {}};
  for (int i = 0; i < count(); ++i) lobes.axes.push_back(Icosahedron::instance().vertex(i));
  return lobes;
}

Eigen::Vector3f AmbientDiceSrbf::reconstruct(const float* coefficients, const Eigen::Vector3d& d) const {
  const Icosahedron& ico = Icosahedron::instance();
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (int i : kPairs) {
    // The sign of one dot product picks the member of the pair that faces d.
    const double c = ico.vertex(i).dot(d);
    const int facing = c >= 0.0 ? i : i ^ 3;
    const double weight = functions_.lobe(std::abs(c));
    for (int channel = 0; channel < 3; ++channel)
      sum[channel] += weight * coefficients[channel * Icosahedron::kVertexCount + facing];
  }
  return sum.cast<float>();
}

namespace {

// The paper's lobes (cos² alone) and the SRBF mix of cos² and cos⁴ (docs/BASES.md).
const BasisRegistration kLobes({30, {"ad-cos2", "ad-srbf"}, {},
                                [](const std::string& name, const BasisParameters&) -> std::unique_ptr<Basis> {
                                  if (name == "ad-cos2") return std::make_unique<AmbientDiceSrbf>(name, 1.0, 0.0);
                                  if (name == "ad-srbf") return std::make_unique<AmbientDiceSrbf>(name, 0.7, 0.3);
                                  return nullptr;
                                }});

}  // namespace

nlohmann::json AmbientDiceSrbfFunctions::describe() const {
  return {{"type", "icosahedron-lobes"},
          {"per_vertex", nlohmann::json::array({"lobe weight"})},
          {"lobe", "f_i(n) = cos2 c^2 + cos4 c^4, c = max(0, vertices[i].n)"},
          {"cos2", cos2Coefficient()},
          {"cos4", cos4Coefficient()}};
}

}  // namespace baker
