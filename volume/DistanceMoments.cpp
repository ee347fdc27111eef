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

double DistanceMapLayout::sharpness() const { return std::log(2.0) / -std::log(std::cos(std::sqrt(M_PI) / size)); }

Eigen::Vector3d DistanceMapLayout::texelDirection(int texel) const {
  return octahedralDecode(Eigen::Vector2d((texel % size + 0.5) / size, (texel / size + 0.5) / size));
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
    : layout_(layout), sharpness_(layout.sharpness()), cutoff_(std::pow(kNegligibleWeight, 1.0 / sharpness_)) {
  for (int t = 0; t < layout.texels(); ++t) texelDirections_.push_back(layout.texelDirection(t));
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
}

bool DistanceMomentsAccumulator::lobeWeight(double cosine, double sharpness, double cutoff, double* weight) {
  if (cosine <= cutoff) return false;
  *weight = std::exp(sharpness * std::log(cosine));
  return true;
}

void DistanceMomentsAccumulator::add(const Eigen::Vector3f* directions, const float* distances, int count) {
  for (int r = 0; r < count; ++r) {
    const Eigen::Vector3d d = directions[r].cast<double>();
    const double distance = std::min(double(distances[r]) / layout_.cap, 1.0);
    const double escaped = std::isinf(distances[r]) ? 1.0 : 0.0;
    for (std::size_t t = 0; t < texelDirections_.size(); ++t) {
      const double c = texelDirections_[t].dot(d);
      if (c > nearestCosine_[t]) {
        nearestCosine_[t] = c;
        nearestDistance_[t] = distance;
        nearestEscaped_[t] = escaped;
      }
      double w;
      if (!lobeWeight(c, sharpness_, cutoff_, &w)) continue;
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
}

DistanceLatticeWeights::DistanceLatticeWeights(const DistanceMapLayout& layout, const Eigen::Vector3f* directions,
                                               int count)
    : rays_(count) {
  const double sharpness = layout.sharpness(), cutoff = std::pow(kNegligibleWeight, 1.0 / sharpness);
  nearestRay_.assign(std::size_t(layout.texels()), -1);
  nearestCosine_.assign(nearestRay_.size(), -2.0);
  texelStart_.reserve(std::size_t(layout.texels()) + 1);
  texelStart_.push_back(0);
  for (int t = 0; t < layout.texels(); ++t) {
    const Eigen::Vector3d texel = layout.texelDirection(t);
    for (int r = 0; r < count; ++r) {
      // As the ray-by-ray sums take it: a cosine of a cast expression adds its terms in another order.
      const Eigen::Vector3d d = directions[r].cast<double>();
      const double c = texel.dot(d);
      if (c > nearestCosine_[t]) nearestCosine_[t] = c, nearestRay_[t] = r;
      double w;
      if (!DistanceMomentsAccumulator::lobeWeight(c, sharpness, cutoff, &w)) continue;
      ray_.push_back(r);
      weight_.push_back(w);
    }
    texelStart_.push_back(int(ray_.size()));
  }
}

bool DistanceMomentsAccumulator::holdsTheSameSumsAs(const DistanceMomentsAccumulator& other) const {
  return weight_ == other.weight_ && sum_ == other.sum_ && sumSquares_ == other.sumSquares_ &&
         escaped_ == other.escaped_ && nearestCosine_ == other.nearestCosine_ &&
         nearestDistance_ == other.nearestDistance_ && nearestEscaped_ == other.nearestEscaped_;
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
