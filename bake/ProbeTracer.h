#pragma once
#include <Eigen/Core>
#include <vector>

#include "scene/RayTracer.h"
#include "scene/Scene.h"

namespace baker {

// Radiance arriving at a probe along each direction of a fixed set. Today that is the
// emission of the surface each ray hits first (single-sided materials emit from the front).
class ProbeTracer {
 public:
  ProbeTracer(const Scene& scene, const RayTracer& tracer, std::vector<Eigen::Vector3f> directions);

  std::size_t directionCount() const { return directions_.size(); }
  // Writes directionCount() RGB radiance values.
  void trace(const Eigen::Vector3f& position, Eigen::Vector3f* radiance) const;

 private:
  const Scene& scene_;
  const RayTracer& tracer_;
  std::vector<Eigen::Vector3f> directions_;
};

}  // namespace baker
