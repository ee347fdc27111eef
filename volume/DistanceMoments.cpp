#include "volume/DistanceMoments.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace baker {
namespace {

double signOf(double x) { return x < 0.0 ? -1.0 : 1.0; }

// Weights below this share of a texel's peak are left out: max(0, c·ω)^k < 1e-4.
constexpr double kNegligibleWeight = 1e-4;

}  // namespace

double DistanceMapLayout::sharpness() const {
  // A texel's half width past 90° (N = 1) leaves no power that halves there: the broadest lobe.
  const double halfWidthCosine = std::cos(std::sqrt(M_PI) / size);
  if (!(halfWidthCosine > 0.0)) return 1.0;
  return std::max(1.0, std::round(std::log(2.0) / -std::log(halfWidthCosine)));
}

Eigen::Vector3d DistanceMapLayout::texelDirection(int texel) const {
  return octahedralDecode(Eigen::Vector2d((texel % size + 0.5) / size, (texel / size + 0.5) / size));
}

TexelLobes::TexelLobes(const DistanceMapLayout& layout)
    : power_(int(layout.sharpness())), cutoff_(std::pow(kNegligibleWeight, 1.0 / power_)) {
  for (int t = 0; t < layout.texels(); ++t) {
    const Eigen::Vector3d d = layout.texelDirection(t);
    x_.push_back(d.x()), y_.push_back(d.y()), z_.push_back(d.z());
  }
}

double TexelLobes::weight(double cosine) const {
  double result = 1.0, square = cosine;
  for (int n = power_;; square *= square) {
    if (n & 1) result *= square;
    if ((n >>= 1) == 0) return result;
  }
}

Eigen::Vector2d octahedralEncode(const Eigen::Vector3d& d) {
  const double l1 = std::abs(d.x()) + std::abs(d.y()) + std::abs(d.z());
  Eigen::Vector2d p(d.x() / l1, d.z() / l1);
  if (d.y() < 0.0) p = Eigen::Vector2d((1.0 - std::abs(p.y())) * signOf(p.x()), (1.0 - std::abs(p.x())) * signOf(p.y()));
  return 0.5 * (p + Eigen::Vector2d::Ones());
}

Eigen::Vector3d octahedralDecode(const Eigen::Vector2d& uv) {
  Eigen::Vector2d p = 2.0 * uv - Eigen::Vector2d::Ones();
  const double y = 1.0 - std::abs(p.x()) - std::abs(p.y());
  if (y < 0.0) p = Eigen::Vector2d((1.0 - std::abs(p.y())) * signOf(p.x()), (1.0 - std::abs(p.x())) * signOf(p.y()));
  return Eigen::Vector3d(p.x(), y, p.y()).normalized();
}

DistanceMomentsAccumulator::DistanceMomentsAccumulator(const DistanceMapLayout& layout)
    : layout_(layout), lobes_(layout) {
  reset();
}

void DistanceMomentsAccumulator::reset() {
  weight_.assign(std::size_t(layout_.texels()), 0.0);
  sum_.assign(weight_.size(), 0.0);
  sumSquares_.assign(weight_.size(), 0.0);
  escaped_.assign(weight_.size(), 0.0);
  nearestCosine_.assign(weight_.size(), -2.0);
  nearestDistance_.assign(weight_.size(), 1.0);
  nearestEscaped_.assign(weight_.size(), 0.0);
  unreached_ = int(weight_.size());
}

void DistanceMomentsAccumulator::add(const Eigen::Vector3f* directions, const float* distances, int count) {
  const int texels = lobes_.texels();
  cosines_.resize(std::size_t(texels));
  reached_.resize(std::size_t(texels));
  for (int r = 0; r < count; ++r) {
    const double distance = std::min(double(distances[r]) / layout_.cap, 1.0);
    const double escaped = std::isinf(distances[r]) ? 1.0 : 0.0;
    // A ray reaches a sixth of the texels or fewer: they are listed without a branch (one taken at
    // random for a sixth of 64 texels mispredicts several times a ray), then summed.
    const Eigen::Vector3d d = directions[r].cast<double>();
    int reached = 0;
    for (int t = 0; t < texels; ++t) {
      const double c = lobes_.cosine(t, d);
      cosines_[std::size_t(t)] = c;
      reached_[std::size_t(reached)] = t;
      reached += lobes_.reaches(c);
    }
    if (unreached_ > 0)
      for (int t = 0; t < texels; ++t)
        if (cosines_[t] > nearestCosine_[t]) {
          nearestCosine_[t] = cosines_[t];
          nearestDistance_[t] = distance;
          nearestEscaped_[t] = escaped;
        }
    for (int k = 0; k < reached; ++k) {
      const std::size_t t = std::size_t(reached_[std::size_t(k)]);
      const double w = lobes_.weight(cosines_[t]);
      unreached_ -= weight_[t] == 0.0;
      weight_[t] += w;
      sum_[t] += w * distance;
      sumSquares_[t] += w * distance * distance;
      escaped_[t] += w * escaped;
    }
  }
}

void DistanceMomentsAccumulator::add(const DistanceLatticeWeights& weights, const float* distances) {
  if (weights.texelStart_.size() != weight_.size() + 1)
    throw std::logic_error("DistanceMomentsAccumulator: lattice weights of a map of another size");
  // Each ray is read by several texels: its values are worked out once.
  rayDistance_.resize(std::size_t(weights.rays_));
  rayEscaped_.resize(rayDistance_.size());
  for (int r = 0; r < weights.rays_; ++r) {
    rayDistance_[r] = std::min(double(distances[r]) / layout_.cap, 1.0);
    rayEscaped_[r] = std::isinf(distances[r]) ? 1.0 : 0.0;
  }
  for (std::size_t t = 0; t < weight_.size(); ++t) {
    const int nearest = weights.nearestRay_[t];
    if (nearest >= 0 && weights.nearestCosine_[t] > nearestCosine_[t]) {
      nearestCosine_[t] = weights.nearestCosine_[t];
      nearestDistance_[t] = rayDistance_[nearest];
      nearestEscaped_[t] = rayEscaped_[nearest];
    }
    double weight = weight_[t], sum = sum_[t], sumSquares = sumSquares_[t], escaped = escaped_[t];
    for (int k = weights.texelStart_[t]; k < weights.texelStart_[t + 1]; ++k) {
      const int r = weights.ray_[k];
      const double w = weights.weight_[k], distance = rayDistance_[r];
      weight += w;
      sum += w * distance;
      sumSquares += w * distance * distance;
      escaped += w * rayEscaped_[r];
    }
    weight_[t] = weight, sum_[t] = sum, sumSquares_[t] = sumSquares, escaped_[t] = escaped;
  }
  unreached_ = int(std::count(weight_.begin(), weight_.end(), 0.0));
}

DistanceLatticeWeights::DistanceLatticeWeights(const DistanceMapLayout& layout, const Eigen::Vector3f* directions,
                                               int count)
    : rays_(count) {
  const TexelLobes lobes(layout);
  nearestRay_.assign(std::size_t(layout.texels()), -1);
  nearestCosine_.assign(nearestRay_.size(), -2.0);
  texelStart_.reserve(std::size_t(layout.texels()) + 1);
  texelStart_.push_back(0);
  for (int t = 0; t < layout.texels(); ++t) {
    for (int r = 0; r < count; ++r) {
      const double c = lobes.cosine(t, directions[r].cast<double>());
      if (c > nearestCosine_[t]) nearestCosine_[t] = c, nearestRay_[t] = r;
      if (!lobes.reaches(c)) continue;
      ray_.push_back(r);
      weight_.push_back(lobes.weight(c));
    }
    texelStart_.push_back(int(ray_.size()));
  }
}

bool DistanceMomentsAccumulator::holdsTheSameSumsAs(const DistanceMomentsAccumulator& other) const {
  if (weight_ != other.weight_ || sum_ != other.sum_ || sumSquares_ != other.sumSquares_ || escaped_ != other.escaped_)
    return false;
  for (std::size_t t = 0; t < weight_.size(); ++t)
    if (weight_[t] == 0.0 && (nearestCosine_[t] != other.nearestCosine_[t] ||
                              nearestDistance_[t] != other.nearestDistance_[t] ||
                              nearestEscaped_[t] != other.nearestEscaped_[t]))
      return false;
  return true;
}

void DistanceMomentsAccumulator::write(float* moments) const {
  for (std::size_t t = 0; t < weight_.size(); ++t) {
    const bool reached = weight_[t] > 0.0;
    const double nearest = nearestDistance_[t];
    moments[2 * t] = float(reached ? sum_[t] / weight_[t] : nearest);
    moments[2 * t + 1] = float(reached ? sumSquares_[t] / weight_[t] : nearest * nearest);
    if (layout_.skyVisibility)
      moments[weight_.size() * 2 + t] = float(reached ? escaped_[t] / weight_[t] : nearestEscaped_[t]);
  }
}

TexelBlend blendTexels(const DistanceMapLayout& layout, const Eigen::Vector3d& d) {
  const Eigen::Vector2d uv = octahedralEncode(d);
  const int n = layout.size;
  int lo[2];
  double f[2];
  for (int a = 0; a < 2; ++a) {
    const double x = uv[a] * n - 0.5;
    lo[a] = std::clamp(int(std::floor(x)), 0, n - 2);
    f[a] = std::clamp(x - lo[a], 0.0, 1.0);
  }
  TexelBlend blend;
  for (int corner = 0; corner < 4; ++corner) {
    const int di = corner & 1, dj = corner >> 1;
    blend.weight[corner] = (di ? f[0] : 1.0 - f[0]) * (dj ? f[1] : 1.0 - f[1]);
    blend.texel[corner] = lo[0] + di + n * (lo[1] + dj);
  }
  return blend;
}

DistanceMomentsRead readDistanceMoments(const DistanceMapLayout& layout, const float* moments, const Eigen::Vector3d& d) {
  const TexelBlend blend = blendTexels(layout, d);
  DistanceMomentsRead read;
  read.open = true;
  for (int corner = 0; corner < 4; ++corner) {
    const double w = blend.weight[corner];
    const int t = blend.texel[corner];
    read.mean += w * moments[2 * t];
    read.meanSquare += w * moments[2 * t + 1];
    if (w > 0.0 && moments[2 * t] < 1.0f) read.open = false;
  }
  read.mean *= layout.cap;
  read.meanSquare *= layout.cap * layout.cap;
  return read;
}

double leakWeight(const DistanceMapLayout& layout, const float* moments, const Eigen::Vector3d& probe,
                  const Eigen::Vector3d& point, const Eigen::Vector3d& normal, double spacing) {
  // The paper's floor and crush threshold, divided by 1.2 with its back-face weight.
  constexpr double kNormalBiasSpacings = 0.25, kFloor = 1e-6 / 1.2, kCrush = 0.2 / 1.2;
  const Eigen::Vector3d biased = point + kNormalBiasSpacings * spacing * normal;
  const Eigen::Vector3d fromProbe = biased - probe;
  const double r = fromProbe.norm();
  // On the probe nothing can hide one from the other; beyond double's range there is no direction.
  if (!(r > 0.0) || !std::isfinite(r)) return 1.0;
  const DistanceMomentsRead read = readDistanceMoments(layout, moments, fromProbe / r);
  if (read.open) return 1.0;
  const Eigen::Vector3d toProbe = -fromProbe / r;
  const double facing = 0.5 * (toProbe.dot(normal) + 1.0);
  double weight = (facing * facing + 0.2) / 1.2;
  if (r > read.mean) {
    const double variance = std::abs(read.meanSquare - read.mean * read.mean);
    const double beyond = r - read.mean;
    const double chebyshev = variance / (variance + beyond * beyond);
    weight *= chebyshev * chebyshev * chebyshev;
  }
  if (!(weight >= kFloor)) weight = kFloor;
  if (weight < kCrush) weight *= weight * weight / (kCrush * kCrush);
  return weight;
}

}  // namespace baker
