#pragma once
#include <Eigen/Core>
#include <vector>

#include "bake/Transport.h"
#include "scene/RayTracer.h"
#include "scene/Scene.h"

namespace baker {

// Punctual lights as a probe itself receives them. A point, spot or directional light is a
// delta in direction that no probe ray can hit, so each unoccluded light adds its exact SH
// coefficients instead: irradiance E⊥ (on a surface facing it) times Y_lm(ω) towards the light.
// The bake turns these into basis coefficients through the clamped-cosine convolution and the
// exact SH→basis projection, with no sampling error.
class PunctualAtProbe {
 public:
  // SH order of the delta's expansion. The clamped cosine's bands fall as l^-5/2, so the moments
  // with any of the bases converge well before it (PunctualAtProbeTest checks against a dense
  // quadrature).
  static constexpr int kShOrder = 24;
  static constexpr int kShCount = (kShOrder + 1) * (kShOrder + 1);

  PunctualAtProbe(const Scene& scene, const RayTracer& tracer) : scene_(scene), tracer_(tracer) {}

  bool empty() const { return scene_.lights.empty(); }
  // E⊥ and direction of each light at `position`, unshadowed (zero irradiance when behind a spot's cone).
  struct Arrival {
    Eigen::Vector3f direction;
    Eigen::Vector3f irradiance;
    float distance;
  };
  Arrival arrival(const PunctualLight& light, const Eigen::Vector3f& position) const;

  // The lights that reach `position` unoccluded (shadow rays from the probe).
  std::vector<Arrival> visibleLights(const Eigen::Vector3f& position, RayCounts* counts) const;
  // Adds E⊥·Y(ω) in RGB of each arrival to sh (kShCount × 3, column-major).
  static void addHarmonics(const std::vector<Arrival>& arrivals, double* sh);

 private:
  const Scene& scene_;
  const RayTracer& tracer_;
};

}  // namespace baker
