#pragma once
#include <Eigen/Core>
#include <string>
#include <vector>

#include "basis/Basis.h"
#include "basis/GramOperators.h"
#include "basis/StoredSignal.h"
#include "volume/DistanceMoments.h"
#include "volume/SkyRadiance.h"

namespace baker {

// What a change of sky does to a probe's coefficients, seen through the probe's stored sky
// visibility: per channel c, a matrix R_c with Δc_c = R_c · v, v the probe's visibility as stored.
// The sky reaches a probe directly as V(ω) ΔL(ω) (ΔL: the new sky's texels less the old's); that
// product is stored as a bake stores radiance: to SH band kProductOrder, then the basis's fit of SH
// radiance, G⁻¹B_sh (radiance) or G⁻¹B_sh·diag(A_l h_l) (irradiance, with the bake's band window).
// Integrals run over the sky's texels, 2 × 2 Gauss points each, so a sun stays a sun.
//
// V(ω) is read from:
// - the basis's visibility coefficients (v: those): for radiance their functions' sum, to SH band
//   kRadianceVisibilityOrder; for irradiance, which stores (1/π)∫V max(0, n·ω) dω, that smoothing
//   and the bake's band window undone band by band (π/(A_l h_l); π/A_l = 1, 3/2, 4) up to band 2,
//   beyond which the clamped cosine leaves too little to undo (A_3 = 0), or the window's last band;
// - rather, when the volume has them, the distance map's sky visibility texels
//   (DistanceMapLayout::skyVisibility; per texel the share of the lobe's rays that escaped),
//   blended bilinearly as leak-aware reads blend the moments (v: the texels). They hold V's
//   detail, a window's edge against the sun, which band 2 cannot. The map alone: mixing in the
//   coefficients' low bands (sharper there) makes a constant sky's change exact but reads their
//   difference from the map at a sun's direction, which costs more than it saves (RELIGHTING.md).
// Exact where the visibility is (open sky, V = 1); elsewhere V is as sharp as its texels or bands,
// which docs/RELIGHTING.md measures. R is linear in ΔL, and exactly 0 for ΔL = 0.
class SkyTransfer {
 public:
  static constexpr int kIrradianceVisibilityOrder = 2;
  static constexpr int kRadianceVisibilityOrder = 8;
  // The clamped cosine's band 16 is 0.15 % of its band 0.
  static constexpr int kProductOrder = 16;

  // Reads the map when `map` has a size and carries the sky's visibility, else the coefficients.
  // NumericalError naming the basis when its Gram matrix cannot be inverted (as a bake would).
  SkyTransfer(const Basis& basis, StoredSignal signal, const BandWindow& window, const DistanceMapLayout& map);

  bool readsMap() const { return map_.size > 0; }
  // How V(ω) is read, in words, for reports.
  std::string visibilitySource() const;
  // R_c for each of the basis's three channels, for the sky changing from `before` to `after`
  // (skies of SkyRadiance's size).
  std::vector<Eigen::MatrixXd> operators(const SkyRadiance& before, const SkyRadiance& after) const;
  // With a map: per RGB channel (rows) and map texel (columns), the flux of `sky` through the
  // texel's bilinear share, so that flux · v = ∫ V(ω) L(ω) dω, V blended from the map v as above.
  Eigen::Matrix3Xd mapFlux(const SkyRadiance& sky) const;

 private:
  struct Node {
    Eigen::Vector3d direction;
    double weight;
    int texel;  // of the sky
    TexelBlend blend;
  };
  // Y_n (rows) at nodes [first, first + count) (columns).
  Eigen::MatrixXd harmonicsAt(std::size_t first, std::size_t count) const;
  // The nodes' bilinear weights on the map's texels: count × texels.
  Eigen::MatrixXd blendsAt(std::size_t first, std::size_t count) const;

  const Basis& basis_;
  DistanceMapLayout map_{0, 0.0};
  int visibilityOrder_ = 0;
  Eigen::MatrixXd fromVisibility_;       // V's SH (visibility order) ← coefficients
  std::vector<Eigen::MatrixXd> fromSh_;  // per channel: coefficients ← SH radiance to kProductOrder
  std::vector<Node> nodes_;
};

}  // namespace baker
