#pragma once
#include <string>
#include <vector>

#include "basis/AmbientDiceSrbf.h"
#include "basis/Basis.h"

namespace baker {

// Nine Ambient Dice SRBF lobes for the radiance above surfaces facing one axis, after the seed
// post's hemispherical Ambient Dice. The icosahedron is turned so that the centre of its face
// (1, Φ, 0), (0, 1, Φ), (Φ, 0, 1) — direction (1, 1, 1)/√3 — points along +Y (glTF's up), by the
// rotation about (−1, 0, 1)/√2 through arccos(1/√3); the nine vertices within 120° of straight
// up are kept, in the icosahedron's order (all but 3, 7 and 11, the opposite face): three 37.4°
// from up, three 79.2°, three 100.8°. Each carries ad-srbf's lobe. For another axis (walls,
// ceilings) the nine are then turned by the shortest rotation from +Y to it; for −Y, which has
// no shortest one, by the half turn about +X.
//
// The lobes keep their whole extent, so each stays radial: one diffuse response and one specular
// table serve all of them, and decoders evaluate them as they do ad-srbf. A bake fits them to
// the hemisphere about the axis only (fitFunctions: the lobes cut off at its horizon), so
// radiance from beyond it is not held and reading there extrapolates.
class HemisphereLobes : public SphericalFunctions {
 public:
  static constexpr int kLobes = 9;
  explicit HemisphereLobes(const Eigen::Vector3d& axis);
  int count() const override { return kLobes; }
  void evaluate(const Eigen::Vector3d& direction, double* values) const override;
  nlohmann::json describe() const override;
  std::vector<Eigen::Vector3d> kinkPlanes() const override { return axes_; }
  std::optional<RadialLobes> radialLobes() const override;
  const std::vector<Eigen::Vector3d>& axes() const { return axes_; }
  const Eigen::Vector3d& hemisphereAxis() const { return hemisphereAxis_; }

 private:
  AmbientDiceSrbfFunctions profile_{0.7, 0.3};
  Eigen::Vector3d hemisphereAxis_;
  std::vector<Eigen::Vector3d> axes_;
};

// A set's functions where d·up ≥ 0, and 0 below: what a hemispherical bake fits.
class AboveHorizon : public SphericalFunctions {
 public:
  AboveHorizon(const SphericalFunctions& functions, const Eigen::Vector3d& up) : functions_(functions), up_(up) {}
  int count() const override { return functions_.count(); }
  void evaluate(const Eigen::Vector3d& direction, double* values) const override;
  std::vector<Eigen::Vector3d> kinkPlanes() const override;

 private:
  const SphericalFunctions& functions_;
  Eigen::Vector3d up_;
};

// CLI name "ad-hemi9": radiance only (an irradiance bake is refused), the same lobes for R, G, B,
// about a unit axis (default +Y).
class AmbientDiceHemisphere : public Basis {
 public:
  explicit AmbientDiceHemisphere(const Eigen::Vector3d& axis = Eigen::Vector3d::UnitY())
      : lobes_(axis), aboveHorizon_(lobes_, axis) {}
  std::string name() const override { return "ad-hemi9"; }
  std::string family() const override { return "ambient-dice"; }
  const SphericalFunctions& functions(int) const override { return lobes_; }
  const SphericalFunctions& fitFunctions(int) const override { return aboveHorizon_; }
  BasisParameters parameters() const override { return {std::nullopt, lobes_.hemisphereAxis()}; }
  std::optional<Eigen::Vector3d> hemisphere() const override { return lobes_.hemisphereAxis(); }
  int coefficientsPerLookup() const override { return 3 * HemisphereLobes::kLobes; }
  Eigen::Vector3f reconstruct(const float* coefficients, const Eigen::Vector3d& d) const override;

 private:
  HemisphereLobes lobes_;
  AboveHorizon aboveHorizon_;
};

}  // namespace baker
