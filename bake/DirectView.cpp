#include "bake/DirectView.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "bake/PathRandom.h"
#include "bake/PowerHeuristic.h"
#include "bake/RayOffset.h"
#include "bake/ScratchBuffer.h"
#include "scene/Shading.h"

namespace baker {
namespace {

constexpr float kPi = 3.14159265358979f;
// Emitter points seen this close to edge-on are not sampled (their density would overflow).
constexpr float kGrazing = 1e-6f;
// Each kind of sample draws from its own streams, apart from the lattice paths' (ray < R).
constexpr std::uint64_t kSkyStream = 1ull << 40, kEmitterStream = 2ull << 40, kSpotStream = 3ull << 40;

// Point i of a Kronecker sequence (Roberts' R_d: steps of the powers of 1/φ_d, φ_d the root of
// x^(d+1) = x + 1) turned by a Cranley–Patterson shift drawn for the probe: the samples of a kind
// are spread evenly, as the lattice's are, so that on smooth light they add little noise beside
// it, and each point is still uniform on its own, so the estimate stays unbiased.
constexpr double kR2[2] = {0.7548776662466927, 0.5698402909980532};
constexpr double kR3[3] = {0.8191725133961645, 0.6710436067037893, 0.5497004779019703};
float kronecker(double shift, double step, int i) {
  const double x = shift + step * double(i);
  return std::min(float(x - std::floor(x)), 0x1.fffffep-1f);
}

// Arrivals waiting for their visibility rays, traced as one stream. Per thread, so that its
// vectors keep their capacity from probe to probe.
struct Pending {
  std::vector<Ray> rays;
  std::vector<DirectView::Arrival> arrivals;
  ScratchBuffer<bool> blocked;
  void start() {
    rays.clear();
    arrivals.clear();
  }
  void add(const Ray& ray, const DirectView::Arrival& arrival) {
    rays.push_back(ray);
    arrivals.push_back(arrival);
  }
  void resolve(const RayTracer& tracer, std::vector<DirectView::Arrival>* out, std::int64_t* counter) {
    if (rays.empty()) return;
    bool* isBlocked = blocked.reserve(rays.size());
    tracer.occluded(rays.data(), int(rays.size()), isBlocked);
    for (std::size_t k = 0; k < rays.size(); ++k)
      if (!isBlocked[k]) out->push_back(arrivals[k]);
    *counter += std::int64_t(rays.size());
  }
};

}  // namespace

DirectView::DirectView(const Scene& scene, const RayTracer& tracer, const TransportSettings& settings,
                       const EmitterSampler& emitters, const LightAim& aim)
    : scene_(scene),
      tracer_(tracer),
      emitters_(emitters),
      aim_(aim),
      seed_(settings.seed),
      sceneScale_(scene.bounds.isEmpty() ? 1.0f : scene.bounds.diagonal().norm()) {
  samplesSky_ = settings.environment && scene.environment.kind() == Environment::Kind::Map && scene.environment.emits();
  samplesEmitters_ = settings.emission && !emitters.empty();
  samplesSpots_ = settings.punctualLights && settings.bounces > 0 && !aim.empty();
}

ProbeView DirectView::at(const Eigen::Vector3f& position, int latticeRays) const {
  ProbeView view;
  view.sampler = this;
  view.position = position;
  view.latticeDensity = float(double(latticeRays) / (4.0 * M_PI));
  const int perKind = std::max(1, (latticeRays + 3) / 4);
  if (samplesSky()) view.skySamples = perKind;
  if (samplesEmitters()) view.emitterSamples = perKind;
  if (!samplesSpots()) return view;
  const int spotSamples = perKind;
  view.samples.assign(scene_.lights.size(), 0);
  view.aims.assign(scene_.lights.size(), {});
  double total = 0.0;
  for (const int l : aim_.lights()) {
    view.aims[l] = aim_.aim(l, position);
    if (!(view.aims[l].width > 0.0f)) continue;
    view.aimed.push_back(l);
    total += view.aims[l].weight;
  }
  // Each aimed light gets its share of the samples by weight, at least one: fixed counts, so
  // that a light's density is its count times its aim's.
  for (const int l : view.aimed)
    view.samples[l] = std::max(1, int(std::lround(double(spotSamples) * view.aims[l].weight / total)));
  return view;
}

float DirectView::latticeSkyWeight(const ProbeView& view, const Eigen::Vector3f& direction) const {
  if (!samplesSky()) return 1.0f;
  return powerHeuristic(view.latticeDensity, float(view.skySamples) * scene_.environment.pdf(direction));
}

float DirectView::latticeEmitterWeight(const ProbeView& view, const Hit& hit, const Eigen::Vector3f& direction) const {
  if (!samplesEmitters()) return 1.0f;
  // Where the samples never go, the lattice keeps it all.
  const float cosine = std::abs(hit.frontNormal.normalized().dot(direction));
  if (!(cosine >= kGrazing)) return 1.0f;
  const float pdf = emitters_.pdfArea(hit.instance, hit.triangle) * hit.distance * hit.distance / cosine;
  return powerHeuristic(view.latticeDensity, float(view.emitterSamples) * pdf);
}

float DirectView::spotDensity(const ProbeView& view, int light, const Eigen::Vector3f& direction) const {
  return float(view.samples[light]) * LightAim::density(view.aims[light], direction);
}

float DirectView::latticeSpotWeight(const ProbeView& view, int light, const Eigen::Vector3f& direction) const {
  if (view.aimed.empty()) return 1.0f;
  return powerHeuristic(view.latticeDensity, spotDensity(view, light, direction));
}

void DirectView::sample(const ProbeView& view, std::uint64_t probeId, std::vector<Arrival>* arrivals,
                        RayCounts* counts) const {
  arrivals->clear();
  if (samplesSky()) sampleSky(view, probeId, arrivals, counts);
  if (samplesEmitters()) sampleEmitters(view, probeId, arrivals, counts);
  if (!view.aimed.empty()) sampleSpots(view, probeId, arrivals, counts);
}

std::vector<DirectView::Arrival> DirectView::fromSky(const std::vector<Arrival>& arrivals) {
  std::vector<Arrival> sky;
  for (const Arrival& a : arrivals)
    if (std::isinf(a.distance)) sky.push_back(a);
  return sky;
}

void DirectView::sampleSky(const ProbeView& view, std::uint64_t probeId, std::vector<Arrival>* arrivals,
                           RayCounts* counts) const {
  thread_local Pending pending;
  pending.start();
  const float m = float(view.skySamples);
  PathRandom shift(seed_, probeId, kSkyStream);
  const double s1 = shift.uniform(), s2 = shift.uniform();
  for (int j = 0; j < view.skySamples; ++j) {
    const float xi1 = kronecker(s1, kR2[0], j), xi2 = kronecker(s2, kR2[1], j);
    const Environment::Sample s = scene_.environment.sample(xi1, xi2);
    if (!(s.pdf > 0.0f)) continue;
    const float weightOverDensity = powerHeuristic(m * s.pdf, view.latticeDensity) / (m * s.pdf);
    const Eigen::Vector3f irradiance = s.radiance * weightOverDensity;
    if (!(irradiance.maxCoeff() > 0.0f) || !irradiance.allFinite()) continue;
    pending.add({view.position, s.direction, 0.0f, std::numeric_limits<float>::infinity()},
                {s.direction, irradiance, std::numeric_limits<float>::infinity()});
  }
  pending.resolve(tracer_, arrivals, &counts->directView);
}

void DirectView::sampleEmitters(const ProbeView& view, std::uint64_t probeId, std::vector<Arrival>* arrivals,
                                RayCounts* counts) const {
  // A sample counts where the probe's ray towards it first hits the sampled triangle itself, as
  // a lattice ray must to see that emission: not through a surface just in front of it (a
  // coincident emitter, glass, a decal), nor where an alpha filter lets the ray through.
  struct Candidate {
    Arrival arrival;
    std::uint64_t triangle;
  };
  thread_local std::vector<Candidate> candidates;
  thread_local std::vector<Eigen::Vector3f> directions;
  candidates.clear();
  directions.clear();
  const float m = float(view.emitterSamples);
  PathRandom random(seed_, probeId, kEmitterStream);
  const double s1 = random.uniform(), s2 = random.uniform(), s3 = random.uniform();
  for (int j = 0; j < view.emitterSamples; ++j) {
    const float xiChoice = kronecker(s1, kR3[0], j), xi1 = kronecker(s2, kR3[1], j), xi2 = kronecker(s3, kR3[2], j);
    const EmitterSampler::Sample s = emitters_.sample(xiChoice, xi1, xi2);
    const EmitterSampler::Emitter& e = *s.emitter;
    const Eigen::Vector3f d = s.point - view.position;
    const float distance = d.norm();
    if (!(distance > 0.0f)) continue;
    const Eigen::Vector3f direction = d / distance;
    const float cosLight = -e.frontNormal.dot(direction);
    if (std::abs(cosLight) < kGrazing || (cosLight < 0.0f && !e.doubleSided)) continue;
    Eigen::Vector3f emission = e.emission;
    if (e.textured) {
      SurfacePoint surface;
      locateSurface(scene_, e.mesh, e.triangle, s.u, s.v, &surface);
      emission = surfaceEmission(surface);
    }
    const float density = m * e.pdfArea * distance * distance / std::abs(cosLight);
    const Eigen::Vector3f irradiance = emission * (powerHeuristic(density, view.latticeDensity) / density);
    if (!(irradiance.maxCoeff() > 0.0f) || !irradiance.allFinite()) continue;
    candidates.push_back({{direction, irradiance, distance}, e.globalTriangle});
    directions.push_back(direction);
  }
  Hit hits[8];
  const int count = int(candidates.size());
  for (int first = 0; first < count; first += 8) {
    const int n = std::min(8, count - first);
    tracer_.intersect8(view.position, directions.data() + first, n, hits);
    counts->directView += n;
    for (int i = 0; i < n; ++i)
      if (!hits[i].missed() && scene_.globalTriangle(hits[i].instance, hits[i].triangle) == candidates[first + i].triangle)
        arrivals->push_back(candidates[first + i].arrival);
  }
}

void DirectView::sampleSpots(const ProbeView& view, std::uint64_t probeId, std::vector<Arrival>* arrivals,
                             RayCounts* counts) const {
  thread_local std::vector<Eigen::Vector3f> directions;
  thread_local std::vector<int> aimedAt;
  directions.clear();
  aimedAt.clear();
  PathRandom shift(seed_, probeId, kSpotStream);
  for (const int light : view.aimed) {
    const double s1 = shift.uniform(), s2 = shift.uniform();
    for (int j = 0; j < view.samples[light]; ++j) {
      directions.push_back(LightAim::direction(view.aims[light], kronecker(s1, kR2[0], j), kronecker(s2, kR2[1], j)));
      aimedAt.push_back(light);
    }
  }
  // The aimed rays find their first hits; each hit then checks its light with a shadow ray.
  thread_local Pending pending;
  pending.start();
  Hit hits[8];
  const int aims = int(directions.size());
  for (int first = 0; first < aims; first += 8) {
    const int n = std::min(8, aims - first);
    tracer_.intersect8(view.position, directions.data() + first, n, hits);
    counts->directView += n;
    for (int i = 0; i < n; ++i) {
      const Hit& hit = hits[i];
      if (hit.missed()) continue;
      const Eigen::Vector3f& direction = directions[first + i];
      const int l = aimedAt[first + i];
      const PunctualLight& light = scene_.lights[l];
      SurfacePoint surface;
      locateSurface(scene_, scene_.instances[hit.instance].mesh, hit.triangle, hit.u, hit.v, &surface);
      const Eigen::Vector3f albedo = surfaceAlbedo(surface);
      if (!(albedo.maxCoeff() > 0.0f)) continue;
      // The first hit as the lattice's paths make it: the side the ray arrived from, offset.
      const Eigen::Vector3f front = hit.frontNormal * (1.0f / hit.frontNormal.norm());
      const Eigen::Vector3f normal = hit.frontFace ? front : Eigen::Vector3f(-front);
      const Eigen::Vector3f point = view.position + hit.distance * direction;
      const Eigen::Vector3f origin = point + surfaceRayOffset(point, sceneScale_) * normal;
      const Eigen::Vector3f d = light.position - origin;
      const float lightDistance = d.norm();
      if (!(lightDistance > 0.0f)) continue;
      const Eigen::Vector3f toLight = d / lightDistance;
      const float cosine = normal.dot(toLight);
      if (cosine <= 0.0f) continue;
      float intensity = light.intensity / (lightDistance * lightDistance);
      if (light.type == PunctualLight::Type::Spot) intensity *= light.spotFalloff(-toLight.dot(light.direction));
      const float density = spotDensity(view, l, direction);
      const Eigen::Vector3f radiance = albedo.cwiseProduct(light.color) * (intensity * cosine / kPi);
      const Eigen::Vector3f irradiance = radiance * (powerHeuristic(density, view.latticeDensity) / density);
      if (!(irradiance.maxCoeff() > 0.0f) || !irradiance.allFinite()) continue;
      pending.add({origin, toLight, 0.0f, lightDistance}, {direction, irradiance, hit.distance});
    }
  }
  pending.resolve(tracer_, arrivals, &counts->directViewShadow);
}

}  // namespace baker
