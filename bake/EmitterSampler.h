#pragma once
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "scene/Scene.h"

namespace baker {

// Emissive triangles as light sources for next-event estimation: a triangle is chosen with
// probability proportional to the power it emits (area × luminance of its emissive factor × the
// sides it emits from), then a point uniformly on it. Textures vary emission within a triangle;
// the estimator stays unbiased because the caller shades the sampled point.
class EmitterSampler {
 public:
  explicit EmitterSampler(const Scene& scene);

  bool empty() const { return emitters_.empty(); }
  std::size_t size() const { return emitters_.size(); }

  struct Sample {
    Eigen::Vector3f point{0.0f, 0.0f, 0.0f};
    std::uint32_t instance = 0, triangle = 0;
    float u = 0.0f, v = 0.0f;  // Embree's barycentrics of the point
    float pdfArea = 0.0f;      // per unit area, including the choice of triangle
    Eigen::Vector3f frontNormal{0.0f, 0.0f, 1.0f};  // unit, world space (Scene::frontNormal)
    bool doubleSided = false;  // emits from both sides
  };
  Sample sample(float xiChoice, float xi1, float xi2) const;
  // The per-area density sample() draws a point of this triangle with (0 for non-emitters).
  float pdfArea(std::uint32_t instance, std::uint32_t triangle) const;

 private:
  struct Emitter {
    std::uint64_t globalTriangle;
    std::uint32_t instance, triangle;
    Eigen::Vector3f p0, e1, e2;  // world corner and edges
    Eigen::Vector3f frontNormal;
    bool doubleSided;
    float area;
    float probability;
  };
  std::vector<Emitter> emitters_;  // sorted by globalTriangle for pdf lookups
  std::vector<double> cumulative_;  // running sum of probabilities, last = 1
  const Scene& scene_;
};

}  // namespace baker
