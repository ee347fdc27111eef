#include "bake/LightAim.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "basis/DirectionSet.h"
#include "scene/Environment.h"

namespace baker {
namespace {

// Rays from each light that find its nearest surface.
constexpr int kNearestSurfaceRays = 256;

}  // namespace

LightAim::LightAim(const Scene& scene, const RayTracer& tracer, bool enabled)
    : scene_(scene), sceneScale_(scene.bounds.isEmpty() ? 1.0f : scene.bounds.diagonal().norm()) {
  power_.assign(scene.lights.size(), 0.0);
  nearestSurface_.assign(scene.lights.size(), std::numeric_limits<float>::infinity());
  if (!enabled) return;
  std::vector<Ray> rays;
  for (std::size_t l = 0; l < scene.lights.size(); ++l) {
    const PunctualLight& light = scene.lights[l];
    if (light.type == PunctualLight::Type::Directional) continue;
    const double power = double(luminance(light.color)) * double(light.intensity);
    if (!(power > 0.0) || !std::isfinite(power)) continue;
    rays.clear();
    for (const Eigen::Vector3d& d : sphericalFibonacci(kNearestSurfaceRays).directions)
      rays.push_back({light.position, d.cast<float>(), 0.0f, std::numeric_limits<float>::infinity()});
    Hit hits[8];
    for (std::size_t first = 0; first < rays.size(); first += 8) {
      const int n = int(std::min<std::size_t>(8, rays.size() - first));
      tracer.intersect8(rays.data() + first, n, hits);
      for (int i = 0; i < n; ++i)
        if (!hits[i].missed()) nearestSurface_[l] = std::min(nearestSurface_[l], hits[i].distance);
    }
    if (!std::isfinite(nearestSurface_[l])) continue;
    power_[l] = power;
    lights_.push_back(int(l));
  }
}

LightAim::Aim LightAim::aim(int light, const Eigen::Vector3f& from) const {
  Aim a;
  a.weight = weight(light, from);
  if (!(a.weight > 0.0)) return a;
  const Eigen::Vector3f d = scene_.lights[light].position - from;
  const float distance = d.norm();
  a.axis = d / distance;
  // θ₀ bounded so that the aim never narrows below a thousandth of a radian (float directions)
  // nor widens past a mild preference for the light's half of the sphere.
  const float theta = std::clamp(nearestSurface_[light] / distance, 1e-3f, 1.0f);
  a.width = 0.5f * theta * theta;
  a.logSpan = std::log1p(2.0f / a.width);
  return a;
}

double LightAim::weight(int light, const Eigen::Vector3f& from) const {
  if (!aimsAt(light)) return 0.0;
  // A point on the light, or so close that its distance is lost in the scene's size, has no
  // direction to aim along.
  const float squared = (scene_.lights[light].position - from).squaredNorm();
  if (!(squared > 1e-12f * sceneScale_ * sceneScale_)) return 0.0;
  return power_[light] / double(squared);
}

float LightAim::density(const Aim& aim, const Eigen::Vector3f& direction) {
  if (!(aim.width > 0.0f)) return 0.0f;
  // c/(u + u₀) normalised over u ∈ [0, 2] and the full turn: c = 1 / (2π ln(1 + 2/u₀)).
  // u = 1 − cos θ = |ω − axis|²/2 for unit vectors, which keeps its precision near the axis,
  // where 1 − ω·axis loses it all to rounding (u₀ can be 5e-7).
  const float u = 0.5f * (direction - aim.axis).squaredNorm();
  return 1.0f / (2.0f * float(M_PI) * aim.logSpan * (u + aim.width));
}

Eigen::Vector3f LightAim::direction(const Aim& aim, float xi1, float xi2) {
  // u = u₀·((1 + 2/u₀)^ξ − 1) inverts the distribution of u.
  const float u0 = aim.width;
  const float u = std::min(2.0f, u0 * std::expm1(xi1 * aim.logSpan));
  const float cosTheta = 1.0f - u, sinTheta = std::sqrt(std::max(0.0f, u * (2.0f - u)));
  const float phi = 2.0f * float(M_PI) * xi2;
  // An orthonormal frame about the axis (Duff et al. 2017).
  const Eigen::Vector3f& n = aim.axis;
  const float sign = std::copysign(1.0f, n.z());
  const float a = -1.0f / (sign + n.z()), b = n.x() * n.y() * a;
  const Eigen::Vector3f t(1.0f + sign * n.x() * n.x() * a, sign * b, -sign * n.x());
  const Eigen::Vector3f s(b, sign + n.y() * n.y() * a, -n.y());
  return (sinTheta * std::cos(phi) * t + sinTheta * std::sin(phi) * s + cosTheta * n).normalized();
}

}  // namespace baker
