#include "bake/PunctualAtProbe.h"

#include <algorithm>
#include <memory>
#include <vector>

namespace baker {

PunctualAtProbe::Arrival PunctualAtProbe::arrival(const PunctualLight& light, const Eigen::Vector3f& position) const {
  Arrival a{-light.direction, light.color * light.intensity, std::numeric_limits<float>::infinity()};
  if (light.type == PunctualLight::Type::Directional) return a;
  const Eigen::Vector3f d = light.position - position;
  a.distance = d.norm();
  if (!(a.distance > 0.0f)) {
    a.irradiance.setZero();  // a probe exactly at the light: no direction, no finite irradiance
    return a;
  }
  a.direction = d / a.distance;
  a.irradiance /= a.distance * a.distance;
  if (light.type == PunctualLight::Type::Spot) a.irradiance *= light.spotFalloff(-a.direction.dot(light.direction));
  return a;
}

std::vector<PunctualAtProbe::Arrival> PunctualAtProbe::visibleLights(const Eigen::Vector3f& position,
                                                                      RayCounts* counts) const {
  std::vector<Ray> rays;
  std::vector<Arrival> arrivals;
  for (const PunctualLight& light : scene_.lights) {
    const Arrival a = arrival(light, position);
    if (!(a.irradiance.maxCoeff() > 0.0f) || !a.irradiance.allFinite()) continue;
    rays.push_back({position, a.direction, 0.0f, a.distance});
    arrivals.push_back(a);
  }
  if (rays.empty()) return {};
  const std::unique_ptr<bool[]> blocked(new bool[rays.size()]);
  tracer_.occluded(rays.data(), int(rays.size()), blocked.get());
  counts->directPunctualShadow += std::int64_t(rays.size());
  std::vector<Arrival> visible;
  for (std::size_t k = 0; k < rays.size(); ++k)
    if (!blocked[k]) visible.push_back(arrivals[k]);
  return visible;
}

int PunctualAtProbe::shOrderFor(const SphericalFunctions& functions) {
  const int degree = functions.polynomialDegree();
  return degree >= 0 ? std::min(degree, kMaxShOrder) : kMaxShOrder;
}

void PunctualAtProbe::addExpansion(const SphericalFunctions& functions, const std::vector<Arrival>& arrivals,
                                   double* moments) {
  const int count = functions.count();
  thread_local std::vector<double> y;
  y.resize(count);
  const Eigen::Map<const Eigen::ArrayXd> values(y.data(), count);
  for (const Arrival& a : arrivals) {
    functions.evaluate(a.direction.cast<double>(), y.data());
    // As arrays, two coefficients to an instruction: written as a loop, the compiler could not
    // rule out that the moments overlap the values (they are separate buffers) and did not
    // vectorise it.
    for (int c = 0; c < 3; ++c)
      Eigen::Map<Eigen::ArrayXd>(moments + c * count, count) += double(a.irradiance[c]) * values;
  }
}

}  // namespace baker
