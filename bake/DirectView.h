#pragma once
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "bake/EmitterSampler.h"
#include "bake/LightAim.h"
#include "bake/PunctualAtProbe.h"
#include "bake/Transport.h"
#include "scene/RayTracer.h"
#include "scene/Scene.h"

namespace baker {

class DirectView;

// What one lattice of a probe and its direct-view samples share: where the probe is, the
// lattice's size, and how the samples aim at the punctual lights (DirectView::at).
struct ProbeView {
  const DirectView* sampler = nullptr;
  Eigen::Vector3f position{0.0f, 0.0f, 0.0f};
  float latticeDensity = 0.0f;  // R/4π: the lattice's samples per steradian
  int skySamples = 0, emitterSamples = 0;
  // Per scene light: how many spot samples aim at it (0: none), and how.
  std::vector<int> samples;
  std::vector<LightAim::Aim> aims;
  std::vector<int> aimed;  // the lights with samples > 0
};

// What a probe sees directly that is small and bright, sampled by importance from the probe.
//
// A probe's direction lattice finds a low sun, a lamp's emissive shade or the spot a point light
// makes on a nearby surface with a handful of its directions, or with none, and which it is
// depends on the lattice, not on the seed: the error swings with the ray count and hides from
// seeds. So each probe also draws samples of three kinds, each checked by a ray from the probe:
//   sky       directions by the environment map's luminance (the table surfaces' next-event
//             estimation uses), for a lat-long map; a constant sky is smooth, the lattice's job;
//   emitters  points of emissive triangles chosen by power, uniform on each, counted where the
//             probe's ray towards the point first hits that triangle;
//   spots     directions aimed near a punctual light (LightAim), whose first hit takes that
//             light's next-event term; the lights share the samples by power over squared
//             distance;
// and combines them with the lattice by multiple importance sampling (power heuristic): the
// lattice counts as R samples of density 1/4π, and its sample of the sky, of an emitter's
// emission, or of a first hit's punctual next-event term keeps the lattice's share; each sample
// here takes the rest. The shares of every direction sum to one, so with the lattice in a random
// rotation (drawn from the seed) the sum is unbiased, and small bright sources fall to the
// samples that aim at them. Each kind's samples are spread evenly like the lattice (a shifted
// Kronecker sequence), so that where the light is smooth they add little noise to it.
class DirectView {
 public:
  using Arrival = PunctualAtProbe::Arrival;

  DirectView(const Scene& scene, const RayTracer& tracer, const TransportSettings& settings,
             const EmitterSampler& emitters, const LightAim& aim);

  bool samplesSky() const { return samplesSky_; }
  bool samplesEmitters() const { return samplesEmitters_; }
  bool samplesSpots() const { return samplesSpots_; }
  bool empty() const { return !samplesSky() && !samplesEmitters() && !samplesSpots(); }

  // For a lattice of `latticeRays` directions from `position`: each kind the scene calls for
  // draws R/4 samples.
  ProbeView at(const Eigen::Vector3f& position, int latticeRays) const;

  // The lattice's share of the sky seen along a lattice direction.
  float latticeSkyWeight(const ProbeView& view, const Eigen::Vector3f& direction) const;
  // The lattice's share of the emission of a lattice hit (along unit `direction`).
  float latticeEmitterWeight(const ProbeView& view, const Hit& hit, const Eigen::Vector3f& direction) const;
  // The lattice's share of scene light `light`'s next-event term at the first hit of the
  // lattice direction `direction`.
  float latticeSpotWeight(const ProbeView& view, int light, const Eigen::Vector3f& direction) const;

  // The samples of one probe, as arrivals: direction and E⊥ = L·w/(M·pdf), so that the probe's
  // irradiance gains E⊥·max(0, n·ω) for each, like a punctual light's. The random shifts of
  // each kind's sequence depend only on (seed, probeId).
  void sample(const ProbeView& view, std::uint64_t probeId, std::vector<Arrival>* arrivals,
              RayCounts* counts) const;
  // The arrivals of `arrivals` that are samples of the sky: theirs alone have no distance (+∞).
  static std::vector<Arrival> fromSky(const std::vector<Arrival>& arrivals);

 private:
  // Samples per steradian with which spot samples aim at `light` along `direction`.
  float spotDensity(const ProbeView& view, int light, const Eigen::Vector3f& direction) const;
  void sampleSky(const ProbeView& view, std::uint64_t probeId, std::vector<Arrival>* arrivals,
                 RayCounts* counts) const;
  void sampleEmitters(const ProbeView& view, std::uint64_t probeId, std::vector<Arrival>* arrivals,
                      RayCounts* counts) const;
  void sampleSpots(const ProbeView& view, std::uint64_t probeId, std::vector<Arrival>* arrivals,
                   RayCounts* counts) const;

  const Scene& scene_;
  const RayTracer& tracer_;
  const EmitterSampler& emitters_;
  const LightAim& aim_;
  std::uint64_t seed_;
  float sceneScale_;
  bool samplesSky_ = false, samplesEmitters_ = false, samplesSpots_ = false;
};

}  // namespace baker
