#pragma once
#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "common/UpperBound.h"
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
  // Always inlined: a bake draws one per path vertex, and returned from a call the sample came
  // back through memory in pieces that the caller then read whole, a stall at every draw.
  Sample sample(float xiChoice, float xi1, float xi2) const;
  // The per-area density sample() draws a point of this triangle with (0 for non-emitters).
  float pdfArea(std::uint32_t instance, std::uint32_t triangle) const;

 private:
  std::vector<Emitter> emitters_;   // sorted by globalTriangle for pdf lookups
  std::vector<double> cumulative_;  // running sum of probabilities, last = 1
  // As many buckets as emitters split [0, 1) evenly: guide_[j] counts the running sums that
  // fall in buckets before j, so the emitter of a number in bucket j lies in
  // [guide_[j], guide_[j + 1]]. One more entry closes the last bucket at the last emitter.
  // Empty for a few emitters, which a search of all of them finds sooner.
  std::vector<std::size_t> guide_;
  // The bucket of x among `buckets`, for numbers and running sums alike: computed one way for
  // both, so that rounding cannot put a sum below a number in a later bucket than the number's.
  // A sum that overflowed (infinite or NaN power) goes to the last bucket, as no number is
  // above it.
  static std::size_t bucketOf(double x, std::size_t buckets) {
    return x < 1.0 ? std::min(std::size_t(x * double(buckets)), buckets - 1) : buckets - 1;
  }
  const Scene& scene_;
};

[[gnu::always_inline]] inline EmitterSampler::Sample EmitterSampler::sample(float xiChoice, float xi1,
                                                                             float xi2) const {
  // std::upper_bound of xiChoice in the running sums, searched only among the few entries its
  // bucket of the guide table allows (a search of every entry made a dozen dependent reads in a
  // scene of thousands of emitters), and without branches (upperBound).
  const double x = xiChoice;
  std::size_t from = 0, length = cumulative_.size();
  if (!guide_.empty()) {
    const std::size_t bucket = bucketOf(x, length);
    from = guide_[bucket];
    length = guide_[bucket + 1] - guide_[bucket] + 1;
  }
  const std::size_t index = from + upperBound(cumulative_.data() + from, length, x);
  const Emitter& e = emitters_[std::min(index, emitters_.size() - 1)];
  // Uniform on the triangle: the square-root warp of the unit square.
  const float s = std::sqrt(xi1);
  const float u = s * (1.0f - xi2), v = s * xi2;
  return {e.p0 + u * e.e1 + v * e.e2, u, v, &e};
}

}  // namespace baker
