#pragma once
#include <Eigen/Core>
#include <vector>

#include "bake/Transport.h"
#include "basis/SphericalHarmonics.h"
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
  static constexpr int kMaxShOrder = 24;

  // Expands the deltas to `shOrder` ≤ kMaxShOrder (shOrderFor says how far a basis needs).
  PunctualAtProbe(const Scene& scene, const RayTracer& tracer, int shOrder)
      : scene_(scene), tracer_(tracer), harmonics_(shOrder) {}

  // A set of polynomials of degree d has no moment with harmonics above band d (they are
  // orthogonal to every polynomial of lower degree), so for such bases (SH) the expansion stops
  // at d and loses nothing; any other set takes kMaxShOrder.
  static int shOrderFor(const SphericalFunctions& functions);

  bool empty() const { return scene_.lights.empty(); }
  int shOrder() const { return harmonics_.order(); }
  int shCount() const { return harmonics_.count(); }
  const SphericalHarmonics& harmonics() const { return harmonics_; }
  // E⊥ and direction of each light at `position`, unshadowed (zero irradiance when behind a spot's cone).
  struct Arrival {
    Eigen::Vector3f direction;
    Eigen::Vector3f irradiance;
    float distance;
  };
  Arrival arrival(const PunctualLight& light, const Eigen::Vector3f& position) const;

  // The lights that reach `position` unoccluded (shadow rays from the probe).
  std::vector<Arrival> visibleLights(const Eigen::Vector3f& position, RayCounts* counts) const;
  // E⊥·f(ω) in RGB of each arrival for any function set (functions.count() × 3): its moments in
  // that set, which a radiance fit takes exactly, where SH serve the irradiance fit.
  static void addExpansion(const SphericalFunctions& functions, const std::vector<Arrival>& arrivals, double* moments);

 private:
  const Scene& scene_;
  const RayTracer& tracer_;
  SphericalHarmonics harmonics_;
};

}  // namespace baker
