#include "basis/AmbientDiceHemisphere.h"

#include <Eigen/Geometry>
#include <cmath>

#include "basis/BasisRegistry.h"
#include "basis/Icosahedron.h"

namespace baker {

namespace {

// The shortest rotation from +Y to `axis` (unit), and the half turn about +X for −Y.
Eigen::Matrix3d upTo(const Eigen::Vector3d& axis) {
  // Y × axis = (z, 0, −x); hypot keeps its length exact for the tiniest x and z.
  const double across = std::hypot(axis.x(), axis.z());
  if (across == 0.0)
    return axis.y() > 0.0 ? Eigen::Matrix3d::Identity() : Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitX()).toRotationMatrix();
  // atan2 keeps the angle exact near ±Y, where acos of y = 1 − ε loses it.
  const Eigen::Vector3d turnAbout(axis.z() / across, 0.0, -axis.x() / across);
  return Eigen::AngleAxisd(std::atan2(across, axis.y()), turnAbout).toRotationMatrix();
}

}  // namespace

HemisphereLobes::HemisphereLobes(const Eigen::Vector3d& axis) : hemisphereAxis_(axis) {
  const Eigen::Vector3d faceCentre = Eigen::Vector3d::Ones().normalized();
  const Eigen::AngleAxisd faceUp(std::acos(faceCentre.y()), faceCentre.cross(Eigen::Vector3d::UnitY()).normalized());
  const Eigen::Matrix3d toAxis = upTo(axis);
  for (int i = 0; i < Icosahedron::kVertexCount; ++i) {
    const Eigen::Vector3d turned = faceUp * Icosahedron::instance().vertex(i);
    if (turned.y() > -0.5) axes_.push_back(toAxis * turned);
  }
}

void HemisphereLobes::evaluate(const Eigen::Vector3d& d, double* values) const {
  for (int i = 0; i < kLobes; ++i) {
    const double c = axes_[std::size_t(i)].dot(d);
    values[i] = c > 0.0 ? profile_.lobe(c) : 0.0;
  }
}

std::optional<RadialLobes> HemisphereLobes::radialLobes() const {
  return RadialLobes{[this](double t) { return t > 0.0 ? profile_.lobe(t) : 0.0; }, axes_};
}

nlohmann::json HemisphereLobes::describe() const {
  nlohmann::json axes = nlohmann::json::array();
  for (const Eigen::Vector3d& a : axes_) axes.push_back({a.x() + 0.0, a.y() + 0.0, a.z() + 0.0});
  return {{"type", "hemisphere-lobes"},
          {"axes", axes},
          {"axes_rule",
           "the icosahedron's vertices but 3, 7 and 11, turned about (-1, 0, 1)/sqrt(2) through acos(1/sqrt(3)) so that "
           "(1, 1, 1)/sqrt(3) becomes +Y, then by the shortest rotation from +Y to hemisphere_axis (the half turn about "
           "+X for -Y)"},
          {"hemisphere_axis", {hemisphereAxis_.x() + 0.0, hemisphereAxis_.y() + 0.0, hemisphereAxis_.z() + 0.0}},
          {"lobe", "f_i(n) = cos2 c^2 + cos4 c^4, c = max(0, axes[i].n)"},
          {"cos2", profile_.cos2Coefficient()},
          {"cos4", profile_.cos4Coefficient()},
          {"fitted_over", "the hemisphere d.hemisphere_axis >= 0: beyond it the sum extrapolates"}};
}

Eigen::Vector3f AmbientDiceHemisphere::reconstruct(const float* coefficients, const Eigen::Vector3d& d) const {
  double lobes[HemisphereLobes::kLobes];
  lobes_.evaluate(d, lobes);
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (int i = 0; i < HemisphereLobes::kLobes; ++i)
    for (int channel = 0; channel < 3; ++channel) sum[channel] += lobes[i] * coefficients[channel * HemisphereLobes::kLobes + i];
  return sum.cast<float>();
}

void AboveHorizon::evaluate(const Eigen::Vector3d& d, double* values) const {
  if (up_.dot(d) >= 0.0) {
    functions_.evaluate(d, values);
    return;
  }
  for (int i = 0; i < count(); ++i) values[i] = 0.0;
}

std::vector<Eigen::Vector3d> AboveHorizon::kinkPlanes() const {
  std::vector<Eigen::Vector3d> planes = functions_.kinkPlanes();
  planes.push_back(up_);
  return planes;
}

namespace {

const BasisRegistration kHemisphere({35, {}, {"hemisphere_axis"},
                                     [](const std::string& name, const BasisParameters& p) -> std::unique_ptr<Basis> {
                                       if (name != "ad-hemi9") return nullptr;
                                       return std::make_unique<AmbientDiceHemisphere>(
                                           p.hemisphereAxis.value_or(Eigen::Vector3d::UnitY()));
                                     }});

}  // namespace

}  // namespace baker
