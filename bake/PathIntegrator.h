#pragma once
#include <Eigen/Core>
#include <cstdint>

#include "bake/EmitterSampler.h"
#include "bake/LightAim.h"
#include "bake/Transport.h"
#include "scene/RayTracer.h"
#include "scene/Scene.h"

namespace baker {

struct SurfacePoint;
struct ProbeView;

// Where a probe ray's first reflection happened, for estimators that share what paths bring back
// from surfaces between probes (SharedReflections).
struct FirstReflection {
  Eigen::Vector3f point = Eigen::Vector3f::Zero();   // the vertex's ray origin
  Eigen::Vector3f normal = Eigen::Vector3f::Zero();  // unit, on the side the probe ray arrived from
  Eigen::Vector3f albedo = Eigen::Vector3f::Zero();
  std::uint32_t instance = 0;
  bool frontFace = false;
  bool reflects = false;  // false: the ray escaped, or its hit reflects nothing
};

// Radiance arriving at a probe along fixed directions, one Lambertian path per direction.
//
// A probe ray returns what it meets: emission (single-sided surfaces emit from the front), or
// the sky, and it records sky visibility (1 when it escapes). At each of up to `bounces`
// diffuse reflections the path adds next-event estimates for punctual lights (shadow rays),
// emissive triangles (chosen by power) and the sky (importance sampled), then continues along
// a cosine-distributed direction; emissive triangles and the sky are combined with that
// direction by multiple importance sampling (power heuristic), so each is counted once. Before
// a path continues, its vertex also aims one ray near a punctual light (LightAim), whose first
// hit takes that light's term, combined by MIS with the continuation's. Paths whose weight has
// dropped below a quarter play Russian roulette. Every effect the settings turn off costs no
// rays at all (LightAim's 256 rays per light, once per bake, only when lights reach surfaces).
//
// Work is a wavefront per probe: closest hits go to Embree eight at a time (rtcIntersect8),
// shadow rays of one bounce as one stream (rtcOccluded1M), and the arithmetic of continuing
// paths and of their emitter samples is done eight paths at a time in SIMD lanes.
class PathIntegrator {
 public:
  PathIntegrator(const Scene& scene, const RayTracer& tracer, const TransportSettings& settings);

  // radiance[i] and visibility[i] for directions[i], i < count. The random numbers of ray i
  // depend only on (settings.seed, probeId, i). With `directView`, the directions are the
  // probe's lattice and what it samples by importance is weighted by the lattice's MIS share:
  // the sky seen, the emission of a first hit and punctual lights' next-event term there. With
  // `hitDistance`, hitDistance[i] is how far ray i went to its first hit (+∞ when it escaped).
  // With `skyBounced`, skyBounced[i] is the part of radiance[i] that is the sky's light after one
  // reflection or more (its next-event terms and the continuations that escaped): what a new sky
  // would change beside the sky seen directly. With `firstReflections` and `reflected`, the first
  // hit of ray i is described in firstReflections[i], and what its path brought back from that
  // hit after another reflection or more (every estimate made from the second vertex on; the
  // first hit's own next events and what its continuation finds by MIS stay in radiance[i])
  // goes to reflected[i] instead of radiance[i] (`reflected` alone decides it); its sky part to
  // reflectedSky[i] instead of skyBounced[i], so with skyBounced, give reflectedSky too.
  void trace(const Eigen::Vector3f& position, std::uint64_t probeId, const Eigen::Vector3f* directions, int count,
             Eigen::Vector3f* radiance, float* visibility, RayCounts* counts,
             const ProbeView* directView = nullptr, float* hitDistance = nullptr,
             Eigen::Vector3f* skyBounced = nullptr, FirstReflection* firstReflections = nullptr,
             Eigen::Vector3f* reflected = nullptr, Eigen::Vector3f* reflectedSky = nullptr) const;

  const EmitterSampler& emitters() const { return emitters_; }
  const LightAim& lightAim() const { return lightAim_; }
  // How far a ray starts off the surface it leaves: a few float steps of the point's largest
  // coordinate or of the scene's size, so that the same scene at any scale or place bakes the same.
  float rayOffset(const Eigen::Vector3f& point) const;

 private:
  struct Vertex;
  struct Scratch;
  struct ShadowBatch;
  struct Aimed;
  // `firstHits`: the vertices are the first hits of the probe's lattice `directions`, and their
  // punctual terms keep the lattice's share (DirectView).
  void addNextEvents(Vertex* vertices, int count, Scratch& scratch, Eigen::Vector3f* radiance,
                     Eigen::Vector3f* skyBounced, RayCounts* counts, const ProbeView* firstHits = nullptr,
                     const Eigen::Vector3f* directions = nullptr) const;
  // Before a path continues, each vertex also aims a ray near a punctual light: a surface close
  // to a light, found by the cosine continuation only now and then, lights the path strongly,
  // and the aimed ray finds it often (LightAim), both combined by MIS.
  void aimAtLights(Vertex* vertices, int count, Scratch& scratch, Eigen::Vector3f* radiance,
                   RayCounts* counts) const;
  void addPunctualEvents(Vertex* vertices, int count, Scratch& scratch, Eigen::Vector3f* radiance, RayCounts* counts,
                         const ProbeView* firstHits, const Eigen::Vector3f* directions) const;
  void addEmitterEvents(Vertex* vertices, int count, Scratch& scratch, Eigen::Vector3f* radiance,
                        RayCounts* counts) const;
  void addEnvironmentEvents(Vertex* vertices, int count, Scratch& scratch, Eigen::Vector3f* radiance,
                            Eigen::Vector3f* skyBounced, RayCounts* counts) const;
  // The aimed rays' first hits, each lit by the light it aimed at (one shadow ray each).
  void shadeAimedHits(const Ray* rays, const Aimed* aimed, int aimedRays, Scratch& scratch, Eigen::Vector3f* radiance,
                      RayCounts* counts) const;
  // Draws each vertex's cosine-weighted continuation and plays Russian roulette; the survivors'
  // rays and BSDF pdfs are compacted to the front, sources[i] the vertex ray i leaves (ascending).
  // Returns how many survive.
  int sampleContinuations(Vertex* vertices, int count, Ray* rays, float* bsdfPdf, int* sources) const;
  // Returns how many vertices the continued paths made (in place of the old ones).
  int continuePaths(Vertex* vertices, int count, bool keepVertices, Scratch& scratch, Eigen::Vector3f* radiance,
                    Eigen::Vector3f* skyBounced, RayCounts* counts) const;
  // In a textured scene, locates the surfaces a packet hit and starts loading their texels:
  // texture lookups at scattered hits miss the cache, and a packet's are announced before any
  // is shaded, so that their latencies overlap.
  void locateSurfaces(const Hit* hits, int count, SurfacePoint* surfaces) const;
  // The surface of a hit: in a textured scene the one locateSurfaces stored for its packet
  // (which must have run), else located now in `located`. Without textures there is nothing to
  // prefetch, and a point used at once costs less.
  const SurfacePoint& surfaceAt(const Hit& hit, SurfacePoint* located) const;
  // Always inlined (defined in PathIntegrator.cpp, its only caller): called once per path vertex,
  // the call's own moving of arguments and saving of registers cost a quarter as much as its work.
  [[gnu::always_inline]] inline bool makeVertex(const Hit& hit, const Eigen::Vector3f& albedo,
                                                const Eigen::Vector3f& origin, const Eigen::Vector3f& direction,
                                                const Eigen::Vector3f& throughput, Vertex* vertex) const;

  const Scene& scene_;
  const RayTracer& tracer_;
  TransportSettings settings_;
  EmitterSampler emitters_;
  bool sampleEmitters_;     // emissive triangles light surfaces, and there are some
  bool sampleEnvironment_;  // the sky lights surfaces
  bool textured_;           // the scene has textures
  LightAim lightAim_;
  bool aimFromVertices_;    // path vertices aim at punctual lights (aimAtLights)
  float sceneScale_;
};

}  // namespace baker
