#include "volume/SkyTransfer.h"

#include <fmt/format.h>

#include <cmath>
#include <memory>
#include <stdexcept>

#include "basis/SphericalHarmonics.h"

namespace baker {
namespace {

int shCount(int order) { return (order + 1) * (order + 1); }

// The basis's colour space as a matrix acting on RGB (it is linear: YCoCg's rows are exact in binary).
Eigen::Matrix3d colorSpaceMatrix(ColorSpace space) {
  Eigen::Matrix3d m;
  for (int c = 0; c < 3; ++c) m.col(c) = toColorSpace(space, Eigen::Vector3f::Unit(c)).cast<double>();
  return m;
}

// Nodes per product of harmonics evaluated at once: 289 × 4096 doubles, 9 MB.
constexpr std::size_t kChunk = 4096;

}  // namespace

SkyTransfer::SkyTransfer(const Basis& basis, StoredSignal signal, const BandWindow& window, const DistanceMapLayout& map)
    : basis_(basis) {
  const bool radiance = signal == StoredSignal::Radiance;
  std::unique_ptr<GramOperators> shared;
  for (int c = 0; c < 3; ++c) {
    if (c == 0 || !basis.channelsShareFunctions())
      shared = std::make_unique<GramOperators>(basis.fitFunctions(c), basis.name());
    fromSh_.push_back(radiance ? shared->fromSh(kProductOrder) : shared->irradianceFromSh(kProductOrder, window));
  }
  visibilityOrder_ = radiance ? kRadianceVisibilityOrder : kIrradianceVisibilityOrder;
  // The bake's window zeroes the bands beyond its width: nothing of V is left there to read.
  if (!radiance)
    while (visibilityOrder_ > 0 && window.factor(visibilityOrder_) == 0.0) visibilityOrder_ -= 1;
  const GramOperators visibilityGram(basis.functions(0), basis.name());
  // B_sh(i, j) = ∫ f_i Y_j: the SH of Σ v_i f_i are B_shᵀ v; an irradiance volume's band l holds
  // V's times A_l h_l / π.
  fromVisibility_ = visibilityGram.shMoments(visibilityOrder_).transpose();
  if (!radiance)
    for (int l = 0; l <= visibilityOrder_; ++l)
      fromVisibility_.middleRows(l * l, 2 * l + 1) *= M_PI / (clampedCosineBand(l) * window.factor(l));
  if (map.size > 0 && map.skyVisibility) map_ = map;

  // Two Gauss–Legendre points in z = cos θ times two midpoints in φ per sky texel.
  const SkyRadiance sky;
  const double g = 0.5 / std::sqrt(3.0), dphi = 2.0 * M_PI / sky.width;
  for (int row = 0; row < sky.height; ++row) {
    const double top = std::cos(M_PI * row / sky.height), bottom = std::cos(M_PI * (row + 1) / sky.height);
    for (int column = 0; column < sky.width; ++column)
      for (int a = 0; a < 2; ++a)
        for (int b = 0; b < 2; ++b) {
          const double z = 0.5 * (top + bottom) + (a ? g : -g) * (top - bottom);
          const double phi = 2.0 * M_PI * (double(column) / sky.width - 0.5) + (b + 0.5) * 0.5 * dphi;
          const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
          Node node{{r * std::cos(phi), z, r * std::sin(phi)}, 0.25 * (top - bottom) * dphi, row * sky.width + column, {}};
          if (readsMap()) node.blend = blendTexels(map_, node.direction);
          nodes_.push_back(node);
        }
  }
}

std::string SkyTransfer::visibilitySource() const {
  if (readsMap())
    return fmt::format("each probe's {0} × {0} sky visibility map, blended bilinearly", map_.size);
  return fmt::format("the sky visibility coefficients, as V(w) to SH band {}", visibilityOrder_);
}

Eigen::MatrixXd SkyTransfer::harmonicsAt(std::size_t first, std::size_t count) const {
  const SphericalHarmonics harmonics(kProductOrder);
  Eigen::MatrixXd y(harmonics.count(), Eigen::Index(count));
  for (std::size_t q = 0; q < count; ++q) harmonics.evaluate(nodes_[first + q].direction, y.col(Eigen::Index(q)).data());
  return y;
}

Eigen::MatrixXd SkyTransfer::blendsAt(std::size_t first, std::size_t count) const {
  Eigen::MatrixXd h = Eigen::MatrixXd::Zero(Eigen::Index(count), map_.texels());
  for (std::size_t q = 0; q < count; ++q)
    for (int corner = 0; corner < 4; ++corner)
      h(Eigen::Index(q), nodes_[first + q].blend.texel[corner]) += nodes_[first + q].blend.weight[corner];
  return h;
}

Eigen::Matrix3Xd SkyTransfer::mapFlux(const SkyRadiance& sky) const {
  if (!readsMap()) throw std::logic_error("SkyTransfer::mapFlux: this transfer reads no map");
  Eigen::Matrix3Xd flux = Eigen::Matrix3Xd::Zero(3, map_.texels());
  for (const Node& node : nodes_) {
    const Eigen::Vector3d rgb = node.weight * sky.texel(node.texel % sky.width, node.texel / sky.width);
    for (int k = 0; k < 4; ++k) flux.col(node.blend.texel[k]) += node.blend.weight[k] * rgb;
  }
  return flux;
}

std::vector<Eigen::MatrixXd> SkyTransfer::operators(const SkyRadiance& before, const SkyRadiance& after) const {
  const Eigen::Matrix3d toBasis = colorSpaceMatrix(basis_.colorSpace());
  const int count = shCount(kProductOrder), low = shCount(visibilityOrder_);
  // ∫ Y_n V ΔL_c dω per unit of each stored value: of V's SH, or of the map's texels.
  std::vector<Eigen::MatrixXd> product(3, Eigen::MatrixXd::Zero(count, readsMap() ? map_.texels() : low));
  for (std::size_t first = 0; first < nodes_.size(); first += kChunk) {
    const std::size_t n = std::min(kChunk, nodes_.size() - first);
    const Eigen::MatrixXd y = harmonicsAt(first, n);
    // What each node's ΔL is integrated against: the map's blend weights or V's harmonics.
    const Eigen::MatrixXd against = readsMap() ? blendsAt(first, n) : Eigen::MatrixXd(y.topRows(low).transpose());
    Eigen::MatrixX3d change(Eigen::Index(n), 3);
    for (std::size_t k = 0; k < n; ++k) {
      const Node& node = nodes_[first + k];
      const int t = node.texel;
      const Eigen::Vector3d rgb = after.texel(t % after.width, t / after.width) - before.texel(t % before.width, t / before.width);
      change.row(Eigen::Index(k)) = node.weight * (toBasis * rgb).transpose();
    }
    for (int c = 0; c < 3; ++c) product[std::size_t(c)] += y * change.col(c).asDiagonal() * against;
  }
  std::vector<Eigen::MatrixXd> result;
  for (int c = 0; c < 3; ++c)
    result.push_back(readsMap() ? Eigen::MatrixXd(fromSh_[std::size_t(c)] * product[std::size_t(c)])
                                : Eigen::MatrixXd(fromSh_[std::size_t(c)] * product[std::size_t(c)] * fromVisibility_));
  return result;
}

}  // namespace baker
