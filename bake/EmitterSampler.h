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

  // What shading a sampled point needs, read once per triangle here rather than through the
  // scene's instance, mesh and material tables at every sample.
  struct Emitter {
    std::uint64_t globalTriangle;
    std::uint32_t triangle, mesh;
    Eigen::Vector3f p0, e1, e2;     // world corner and edges
    Eigen::Vector3f frontNormal;    // unit, world space (Scene::frontNormal)
    Eigen::Vector3f emission;       // the material's, which a texture may vary (`textured`)
    float area;
    float pdfArea;                  // per unit area, including the choice of triangle
    bool doubleSided;               // emits from both sides
    bool textured;                  // emission must be looked up at the point (surfaceEmission)
    bool alphaTested;               // MASK or BLEND: the point may not stop a shadow ray
  };
  struct Sample {
    Eigen::Vector3f point;
    float u, v;  // Embree's barycentrics of the point
    const Emitter* emitter;
  };
  Sample sample(float xiChoice, float xi1, float xi2) const;
  // The per-area density sample() draws a point of this triangle with (0 for non-emitters).
  float pdfArea(std::uint32_t instance, std::uint32_t triangle) const;

 private:
  std::vector<Emitter> emitters_;   // sorted by globalTriangle for pdf lookups
  std::vector<double> cumulative_;  // running sum of probabilities, last = 1
  const Scene& scene_;
};

}  // namespace baker
