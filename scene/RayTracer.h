#pragma once
#include <embree3/rtcore.h>

#include <Eigen/Core>
#include <cstdint>

#include "scene/Scene.h"

namespace baker {

// Closest hit of one ray: the triangle (index into Scene::triangles) or kMiss.
struct Hit {
  static constexpr std::uint32_t kMiss = 0xffffffffu;
  std::uint32_t triangle = kMiss;
  float distance = 0.0f;
  bool frontFace = false;  // the ray arrived on the counter-clockwise side
};

// One Embree device and scene over all the triangles of a Scene. Thread-safe for tracing.
class RayTracer {
 public:
  explicit RayTracer(const Scene& scene);
  ~RayTracer();
  RayTracer(const RayTracer&) = delete;
  RayTracer& operator=(const RayTracer&) = delete;

  // Traces up to 8 rays sharing one origin (a probe's rays) as one packet.
  void intersect8(const Eigen::Vector3f& origin, const Eigen::Vector3f* directions, int count, Hit* hits) const;

 private:
  const Scene& scene_;
  RTCDevice device_ = nullptr;
  RTCScene rtcScene_ = nullptr;
};

}  // namespace baker
