#include "basis/GgxLobe.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "basis/Quadrature.h"

namespace baker {

GgxLobe::GgxLobe(const Eigen::Vector3d& normal, const Eigen::Vector3d& view, double roughness) : normal_(normal) {
  if (!(roughness >= 0.0 && roughness <= 1.0)) throw std::invalid_argument("GGX roughness outside [0, 1]");
  const double alpha = roughness * roughness;
  alpha2_ = alpha * alpha;
  // A frame about n whose tangent lies in the plane of n and v (any tangent when v is along n).
  Eigen::Vector3d along = view - normal.dot(view) * normal;
  if (along.norm() < 1e-12) along = normal.unitOrthogonal();
  tangent_ = along.normalized();
  bitangent_ = normal.cross(tangent_);
  cosView_ = std::clamp(normal.dot(view), kMinCosView, 1.0);
  view_ = cosView_ * normal + std::sqrt(1.0 - cosView_ * cosView_) * tangent_;
  reflection_ = 2.0 * cosView_ * normal - view_;
}

double GgxLobe::lambda(double cosine) const {
  const double c2 = cosine * cosine;
  return 0.5 * (std::sqrt(1.0 + alpha2_ * (1.0 - c2) / c2) - 1.0);
}

double GgxLobe::cosineWeighted(const Eigen::Vector3d& omega) const {
  const double cosOmega = normal_.dot(omega);
  if (cosOmega <= 0.0 || alpha2_ == 0.0) return 0.0;  // the mirror has no density: quadrature() holds it
  const Eigen::Vector3d h = (view_ + omega).normalized();
  const double cosH = normal_.dot(h);
  const double denominator = cosH * cosH * (alpha2_ - 1.0) + 1.0;
  const double d = alpha2_ / (M_PI * denominator * denominator);
  const double g2 = 1.0 / (1.0 + lambda(cosView_) + lambda(cosOmega));
  return d * g2 / (4.0 * cosView_);
}

DirectionSet GgxLobe::quadrature(int uNodes, int phiNodes) const {
  std::vector<double> nodes, weights;
  gaussLegendre(uNodes, &nodes, &weights);
  DirectionSet set;
  for (int k = 0; k < uNodes; ++k) {
    // u ∈ (0, 1) is the CDF of cos θ_h under D(h)(n·h).
    const double u = 0.5 * (nodes[std::size_t(k)] + 1.0);
    const double cos2 = (1.0 - u) / (1.0 + (alpha2_ - 1.0) * u);
    const double cosH = std::sqrt(cos2), sinH = std::sqrt(std::max(0.0, 1.0 - cos2));
    for (int p = 0; p < phiNodes; ++p) {
      const double phi = 2.0 * M_PI * (p + 0.5) / phiNodes;
      const Eigen::Vector3d h =
          cosH * normal_ + sinH * (std::cos(phi) * tangent_ + std::sin(phi) * bitangent_);
      const double vDotH = view_.dot(h);
      const Eigen::Vector3d omega = 2.0 * vDotH * h - view_;
      const double cosOmega = normal_.dot(omega);
      if (vDotH <= 0.0 || cosOmega <= 0.0) continue;
      // ρ (n·ω) over the density D(h)(n·h) / (4 v·h) of ω: G2 (v·h) / ((n·v)(n·h)).
      const double g2 = 1.0 / (1.0 + lambda(cosView_) + lambda(cosOmega));
      set.directions.push_back(omega);
      set.weights.push_back(0.5 * weights[std::size_t(k)] / phiNodes * g2 * vDotH / (cosView_ * cosH));
    }
  }
  return set;
}

double GgxLobe::albedo() const {
  const DirectionSet q = quadrature(64, 128);
  double sum = 0.0;
  for (double w : q.weights) sum += w;
  return sum;
}

}  // namespace baker
