#pragma once
#include <Eigen/Core>
#include <memory>
#include <mutex>
#include <vector>

#include "basis/Basis.h"
#include "basis/DiffuseResponse.h"
#include "basis/SpecularBlend.h"
#include "basis/StoredSignal.h"
#include "volume/SkyHarmonics.h"
#include "volume/Volume.h"

namespace baker {

// What a reader gets from a probe's (interpolated) coefficients, whatever signal the volume
// stores (its setting "signal"): irradiance and sky visibility for a normal from either; the
// radiance itself only from a radiance volume, whose irradiance is each function's diffuse
// response (DiffuseResponse), not a second fit.
class VolumeReconstruction {
 public:
  // InputError for a basis or signal the file names wrongly (basisOf, storedSignalOf).
  explicit VolumeReconstruction(const Volume& volume);
  // For coefficients fresh from a bake, before any file records what they hold.
  VolumeReconstruction(std::unique_ptr<Basis> basis, StoredSignal signal);

  const Basis& basis() const { return *basis_; }
  StoredSignal signal() const { return signal_; }
  // E(n) in RGB.
  Eigen::Vector3f irradiance(const float* coefficients, const Eigen::Vector3d& normal) const;
  // (1/π) ∫ V(ω) max(0, n·ω) dω, from coefficients in channel 0's functions.
  double skyVisibility(const float* visibility, const Eigen::Vector3d& normal) const;
  // E(n) in RGB as decoders relight it at run time under `sky` (docs/RELIGHTING.md): the light
  // that is not the sky's, from `rest` (the coefficients less the sky_direct grids'), plus the
  // sky's unoccluded irradiance times the probe's cosine-weighted sky visibility V(n).
  Eigen::Vector3f relitIrradiance(const float* rest, const float* visibility, const Eigen::Vector3d& normal,
                                  const SkyHarmonics& sky) const;
  // L(ω) in RGB: only a radiance volume holds it (`signal()` says; a logic error otherwise).
  Eigen::Vector3f radiance(const float* coefficients, const Eigen::Vector3d& direction) const;
  // The GGX-weighted mean radiance S in RGB for a unit normal, a unit view (towards the eye) and
  // a roughness in [0, 1], blended from L(r) and E(n)/π (basis/SpecularBlend.h), with the
  // blend's weight and albedo there; radiance volumes only, like radiance(). The blend is
  // fitted on the first call (per process and basis).
  struct Specular {
    Eigen::Vector3f value;
    double diffuseWeight = 0.0;
    double albedo = 0.0;  // what S is multiplied by for the radiance a GGX surface with F0 = 1 reflects
  };
  Specular specular(const float* coefficients, const Eigen::Vector3d& normal, const Eigen::Vector3d& view,
                    double roughness) const;

 private:
  // Σ c_i K_i(n) over channel c's functions.
  double diffuse(int channel, const float* coefficients, const Eigen::Vector3d& normal) const;

  std::unique_ptr<Basis> basis_;
  StoredSignal signal_;
  std::vector<std::shared_ptr<const DiffuseResponse>> responses_;  // per channel (radiance only)
  mutable std::once_flag blendFitted_;
  mutable std::shared_ptr<const SpecularBlend> blend_;
};

}  // namespace baker
