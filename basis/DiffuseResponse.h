#pragma once
#include <Eigen/Core>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "basis/Basis.h"
#include "basis/LegendreResponse.h"
#include "basis/SphericalFunctions.h"
#include "basis/SphericalHarmonics.h"

namespace baker {

// The diffuse response of a function set that holds radiance: K_i(n) = ∫ f_i(ω) max(0, n·ω) dω,
// so that a radiance fit L = Σ c_i f_i gives the irradiance E(n) = Σ c_i K_i(n) exactly, where a
// fit of E itself in the same functions would only be E's projection. Radial lobes (the set's
// radialLobes()) share one Legendre series of n·axis_i (basis/LegendreResponse.h). For other sets,
// by the Funk–Hecke theorem K_i(n) = Σ_lm A_l (f_i)_lm Y_lm(n): the set's SH moments scaled by
// the clamped cosine's bands, summed until no response changes by more than 1e-6 of the largest
// (exact at once for polynomials such as SH).
class DiffuseResponse {
 public:
  // NumericalError naming `label` when the sum has not converged by SphericalHarmonics::kMaxOrder.
  DiffuseResponse(const SphericalFunctions& functions, const std::string& label);

  int count() const { return radial_ ? int(axes_.size()) : int(fromSh_.rows()); }
  // count() values K_i(n) for the unit normal n.
  void evaluate(const Eigen::Vector3d& normal, double* response) const;

  // The response as a volume's file states it for decoders (docs/FORMAT.md): "legendre" for
  // radial lobes, "band-factors" for SH; null for other sets, whose response only this library
  // evaluates (the SH moments of piecewise functions, hundreds per function).
  nlohmann::json describe() const;

 private:
  std::optional<LegendreResponse> radial_;
  std::vector<Eigen::Vector3d> axes_;
  SphericalHarmonics harmonics_{0};
  Eigen::MatrixXd fromSh_;  // count × SH count: (f_i)_lm · A_l
  bool isSh_ = false;
};

// The response of channel `channel`'s functions, built once per process for each basis (its name
// and parameters) and function set: it costs the SH moments of the set to the converged order.
// NumericalError as the constructor.
std::shared_ptr<const DiffuseResponse> diffuseResponseOf(const Basis& basis, int channel);

}  // namespace baker
