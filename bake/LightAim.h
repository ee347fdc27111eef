#pragma once
#include <Eigen/Core>
#include <vector>

#include "scene/RayTracer.h"
#include "scene/Scene.h"

namespace baker {

// Directions aimed near punctual lights, for estimating the light that surfaces near a light
// reflect. Seen from a point at distance D from a light, a surface δ from the light is lit like
// 1/δ², and so the reflected light grows like 1/θ² towards the light's direction (θ the angle
// from it) until θ reaches θ₀ = (distance from the light to its nearest surface) / D. An aim is
// the density c/(u + u₀) in u = 1 − cos θ over the whole sphere, u₀ = θ₀²/2: close to the
// light's direction it follows that growth, and far from it it still covers every direction.
// A point weighs lights by power over squared distance when it shares samples among them.
class LightAim {
 public:
  // Traces 256 rays from each point and spot light, once, to find its nearest surface;
  // directional lights, lights with no surface near and lights of no power are not aimed at.
  // Not `enabled`: aims at nothing and traces nothing (no punctual light reaches a surface).
  LightAim(const Scene& scene, const RayTracer& tracer, bool enabled);

  bool empty() const { return lights_.empty(); }
  const std::vector<int>& lights() const { return lights_; }  // scene lights aimed at
  bool aimsAt(int light) const { return power_[light] > 0.0; }

  struct Aim {
    Eigen::Vector3f axis{0.0f, 0.0f, 1.0f};  // unit, towards the light
    float width = 0.0f;                      // u₀; 0: no aim (the point is on the light)
    double weight = 0.0;                     // power / D²; 0 with no aim (double: it may exceed float)
    float logSpan = 0.0f;                    // ln(1 + 2/u₀), the density's normalisation
  };
  Aim aim(int light, const Eigen::Vector3f& from) const;
  // aim(light, from).weight alone, without the rest of the aim.
  double weight(int light, const Eigen::Vector3f& from) const;

  // Per steradian, of one sample of `aim` along unit `direction`.
  static float density(const Aim& aim, const Eigen::Vector3f& direction);
  // The direction of uniform numbers (xi1, xi2): u by inverting the distribution, φ = 2πxi2.
  static Eigen::Vector3f direction(const Aim& aim, float xi1, float xi2);

 private:
  const Scene& scene_;
  float sceneScale_;
  std::vector<double> power_;         // per scene light; 0 when not aimed at
  std::vector<float> nearestSurface_;  // per scene light
  std::vector<int> lights_;
};

}  // namespace baker
