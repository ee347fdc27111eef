#pragma once
#include <embree3/rtcore.h>

#include <Eigen/Core>
#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

#include "scene/Scene.h"

namespace baker {

// Closest hit of one ray: triangle `triangle` of the mesh of instance `instance` (global id
// Scene::globalTriangle(instance, triangle)), or both kMiss when the ray escaped.
struct Hit {
  static constexpr std::uint32_t kMiss = 0xffffffffu;
  std::uint32_t instance = kMiss;
  std::uint32_t triangle = kMiss;
  float u = 0.0f, v = 0.0f;  // barycentric weights of the triangle's second and third corners
  float distance = 0.0f;
  bool frontFace = false;  // the ray arrived on glTF's front side (counter-clockwise in object space)
  // World-space normal of that front side, not normalised: Embree's geometric normal of the hit,
  // so that shading never has to read the triangle's corners again.
  Eigen::Vector3f frontNormal{0.0f, 0.0f, 0.0f};

  bool missed() const { return triangle == kMiss; }
};

// A ray segment: what it meets between tnear and tfar.
struct Ray {
  Eigen::Vector3f origin{0.0f, 0.0f, 0.0f};
  Eigen::Vector3f direction{0.0f, 0.0f, 1.0f};
  float tnear = 0.0f;
  float tfar = std::numeric_limits<float>::infinity();
};

// Hears what a RayTracer traces: the one hook a benchmark has into it (bench/ records the rays
// to replay them with Embree alone, and times Embree's calls). Given at construction and
// called from every tracing thread; an observer that is not thread-safe serves one thread.
class RayObserver {
 public:
  virtual ~RayObserver() = default;
  virtual void closest(const Ray* rays, int count) = 0;    // before each intersect8
  virtual void occlusion(const Ray* rays, int count) = 0;  // before each occluded stream
  virtual bool timesEmbreeCalls() const = 0;
  virtual void embreeCall(double seconds) = 0;             // after each Embree call, when it times them
};

// One Embree device and scene over a Scene. A mesh that several instances use is built once,
// in its own Embree scene, and placed by instance geometries; a mesh used once goes into the
// top-level scene in world space (one BVH level fewer to traverse). MASK and BLEND triangles
// sit in geometries of their own that carry intersection and occlusion filters; opaque
// geometry has none, so it costs nothing extra. Thread-safe for tracing.
class RayTracer {
 public:
  // alphaFilters = false treats MASK and BLEND triangles as opaque (`--no alpha_filters`).
  explicit RayTracer(const Scene& scene, bool alphaFilters = true, RayObserver* observer = nullptr);
  ~RayTracer();
  RayTracer(const RayTracer&) = delete;
  RayTracer& operator=(const RayTracer&) = delete;

  // Traces up to 8 rays sharing one origin (a probe's rays) as one packet (rtcIntersect8).
  void intersect8(const Eigen::Vector3f& origin, const Eigen::Vector3f* directions, int count, Hit* hits) const;
  // Traces up to 8 rays with their own origins and extents (bounce rays) as one packet.
  void intersect8(const Ray* rays, int count, Hit* hits) const;
  // blocked[i]: something stops rays[i] between its tnear and tfar. Streams of rays
  // (rtcOccluded1M), any count.
  void occluded(const Ray* rays, int count, bool* blocked) const;

  // The Embree scene it traces, for a benchmark that times Embree's own calls on it
  // (bench/EmbreeCallForms): tracing goes through the calls above.
  RTCScene embreeScene() const { return rtcScene_; }
  int instancedMeshes() const { return instancedMeshes_; }    // meshes built once and instanced
  int filteredGeometries() const { return filteredGeometries_; }  // geometries with alpha filters

  // What a filter needs to find the surface a candidate hit lies on.
  struct FilterTarget {
    const Scene* scene;
    std::uint32_t mesh;
    std::uint32_t firstTriangle;  // the mesh triangle of the geometry's primitive 0
  };

 private:
  void attachMesh(RTCScene target, std::uint32_t mesh, const Eigen::Matrix4f& transform, unsigned firstId);
  Hit decode(unsigned geomID, unsigned instID, unsigned primID, float u, float v, float distance,
             const Eigen::Vector3f& geometricNormal, const Eigen::Vector3f& direction) const;

  const Scene& scene_;
  bool alphaFilters_ = true;
  RTCDevice device_ = nullptr;
  RTCScene rtcScene_ = nullptr;
  std::vector<RTCScene> meshScenes_;  // per mesh; null unless the mesh is instanced
  // Per instance, Embree's geometric normal of a hit → the world-space front normal. Embree
  // reports it in the space the triangles were built in: object space for an instanced mesh
  // (then the instance's normal transform applies), world space for a mesh placed directly,
  // where the corners' order, and so the normal, flips under a mirroring transform.
  std::vector<Eigen::Matrix3f> frontNormalFromEmbree_;
  std::vector<std::unique_ptr<FilterTarget>> filterTargets_;  // stable addresses for Embree's user data
  int instancedMeshes_ = 0;
  int filteredGeometries_ = 0;
  RayObserver* observer_ = nullptr;
};

}  // namespace baker
