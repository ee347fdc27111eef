#include "bake/PathIntegrator.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "bake/DirectView.h"
#include "bake/PathRandom.h"
#include "bake/PowerHeuristic.h"
#include "bake/RayOffset.h"
#include "bake/ScratchBuffer.h"
#include "scene/Shading.h"

namespace baker {
namespace {

constexpr float kPi = 3.14159265358979f;
constexpr float kInvPi = 1.0f / kPi;
// Below this path weight (largest colour channel), a path survives with probability
// weight / threshold: deep paths of dark scenes stop early, bright ones carry on unchanged.
constexpr float kRouletteThreshold = 0.25f;
// Shadow rays towards a sampled emitter point stop this fraction short of it, so that they do
// not find the emitter itself.
constexpr float kShadowShortening = 1e-4f;

// The straight-line arithmetic of a path step (directions, shadow-ray geometry, MIS weights) is
// done for this many paths at once, in Eigen fixed-size arrays that compile to vector registers.
// Every path goes through the same lane code (a short last block is padded), and a lane's
// operations are those of one path written out in floats (sums of three in the order of
// Eigen's Vector3f, correctly rounded square roots), so a path's result does not depend on its
// lane or block: volumes stay bit-identical at any thread count. Branches, table lookups and
// random draws stay scalar, around the lanes.
constexpr int kLanes = 8;
using Lanes = Eigen::Array<float, kLanes, 1>;
// The quantities of an emitter shadow ray that go into lanes: the vector to the point, the
// vertex's normal, the emitter's normal, its area density.
constexpr std::size_t kEmitterLaneArrays = 10;

// Correctly rounded square roots, as std::sqrt gives (this file is built without errno for
// math functions, so the loop becomes a vector square root): Eigen's packet sqrt is by default
// an approximate reciprocal root and one Newton step, a few ulps off.
Lanes exactSqrt(const Lanes& x) {
  Lanes root;
  for (int j = 0; j < kLanes; ++j) root[j] = std::sqrt(x[j]);
  return root;
}

// cos(2πt) and sin(2πt) for t in [0, 1), to a few float ulps: the angle is reduced to an eighth
// of a turn, where short Taylor polynomials suffice, then turned by the quarter turns taken off.
// The library's sincos costs several times as much, and a path needs one per bounce.
void cosSinTurns(const Lanes& t, Lanes* cosine, Lanes* sine) {
  const Lanes quarters = (4.0f * t + 0.5f).cast<int>().cast<float>();  // the nearest quarter turn, 0 to 4
  const Lanes x = 2.0f * kPi * (t - 0.25f * quarters);                    // within ±π/4
  const Lanes x2 = x * x;
  const Lanes s = x * (1.0f + x2 * (-1.0f / 6 + x2 * (1.0f / 120 + x2 * (-1.0f / 5040 + x2 * (1.0f / 362880)))));
  const Lanes c = 1.0f + x2 * (-0.5f + x2 * (1.0f / 24 + x2 * (-1.0f / 720 + x2 * (1.0f / 40320))));
  // Turned by q quarter turns, (c, s) becomes (turned[q], turned[q + 3]) with indices mod 4:
  // a lookup rather than a switch, whose random branch would be mispredicted three times in four.
  for (int j = 0; j < kLanes; ++j) {
    const float turned[4] = {c[j], -s[j], -c[j], s[j]};
    const int q = int(quarters[j]) & 3;
    (*cosine)[j] = turned[q];
    (*sine)[j] = turned[(q + 3) & 3];
  }
}

// Cosine-distributed directions about unit normals (pdf cosθ/π), through an orthonormal frame
// that has no singularity (Duff et al. 2017). The frame of a unit normal is orthonormal, so a
// direction is unit to float rounding and is not normalised again. Its cosine with the normal
// is the sampled √(1 − ξ1): ξ1 ≤ 1 − 2⁻²⁴ (PathRandom), so the cosine, and the pdf, are never 0.
struct CosineDirections {
  Lanes x, y, z, cosine;
};
CosineDirections cosineDirections(const Lanes& nx, const Lanes& ny, const Lanes& nz, const Lanes& xi1,
                                  const Lanes& xi2) {
  // copysign, not Eigen's sign(), which is 0 at ±0, where the frame needs ±1: a flipped wall
  // normal has z = −0.
  Lanes sign;
  for (int j = 0; j < kLanes; ++j) sign[j] = std::copysign(1.0f, nz[j]);
  const Lanes a = -1.0f / (sign + nz);
  const Lanes b = nx * ny * a;
  Lanes cosPhi, sinPhi;
  cosSinTurns(xi2, &cosPhi, &sinPhi);
  const Lanes r = exactSqrt(xi1);
  const Lanes x = r * cosPhi, y = r * sinPhi, z = exactSqrt(1.0f - xi1);
  // x·t + y·s + z·n with t = (1 + sign·nx²·a, sign·b, −sign·nx) and s = (b, sign + ny²·a, −ny).
  return {x * (1.0f + sign * nx * nx * a) + y * b + z * nx, x * sign * b + y * (sign + ny * ny * a) + z * ny,
          -x * sign * nx - y * ny + z * nz, z};
}

}  // namespace

struct PathIntegrator::Vertex {
  Eigen::Vector3f origin;  // where its rays start: the hit point, offset along the normal
  Eigen::Vector3f normal;  // geometric, unit, on the side the path arrived from
  // The path's throughput to here times the albedo here: every estimate made at the vertex
  // scales by it, and it is the throughput its continuation carries on ((ρ/π)·cosθ over the
  // pdf cosθ/π; divided by the survival chance when Russian roulette plays), so it is
  // multiplied out once.
  Eigen::Vector3f scatteredThroughput;
  // Where the path came from and how: the previous vertex's ray origin, the direction, and
  // its cosine density there; 0 for a probe ray's first hit, which came from the lattice.
  Eigen::Vector3f previous;
  Eigen::Vector3f arrival;
  float arrivalPdf = 0.0f;
  // Σ of the lights' aim weights: from `previous` (as it aimed), then, once this vertex has
  // aimed (aimAtLights), from its own origin, for the vertex its continuation makes.
  double aimTotal = 0.0;
  int path = 0;
  PathRandom random{0, 0, 0};
};

struct PathIntegrator::Aimed {  // a vertex's ray aimed near a light
  int path;
  int light;
  Eigen::Vector3f throughput;  // to the aimed ray's first hit, with the aim's MIS share
};

// Per-thread arrays reused from probe to probe: a bake traces millions of short wavefronts.
struct PathIntegrator::Scratch {
  struct Pending {  // what a shadow ray adds to its path's radiance if nothing blocks it
    int path;
    Eigen::Vector3f contribution;
  };
  // What shading a vertex's sampled point reads once its shadow ray's geometry is worked out.
  struct EmitterPoint {
    const EmitterSampler::Emitter* emitter;
    float xiCoverage;
  };
  ScratchBuffer<Vertex> vertices;
  ScratchBuffer<Ray> rays;
  ScratchBuffer<Pending> pending;
  ScratchBuffer<bool> blocked;
  ScratchBuffer<EmitterPoint> points;
  // The emitter shadow rays' geometry, one array per quantity (kEmitterLaneArrays of them, each
  // padded to whole blocks of lanes), read into lanes with one load each.
  ScratchBuffer<float> emitterLanes;
  ScratchBuffer<SurfacePoint> emitterSurfaces;  // of the points on textured or alpha-tested emitters
  ScratchBuffer<float> pdfs;
  ScratchBuffer<int> sources;  // the vertex each continuation leaves
  ScratchBuffer<Aimed> aimed;
  ScratchBuffer<double> aimWeights;  // of one vertex, per light aimed at
  ScratchBuffer<Ray> shadowRays;
};

PathIntegrator::PathIntegrator(const Scene& scene, const RayTracer& tracer, const TransportSettings& settings)
    : scene_(scene),
      tracer_(tracer),
      settings_(settings),
      emitters_(scene),
      sampleEmitters_(settings.emissiveLights && !emitters_.empty()),
      sampleEnvironment_(settings.environment && scene.environment.emits()),
      textured_(!scene.images.empty()),
      lightAim_(scene, tracer, settings.punctualLights && settings.bounces > 0),
      aimFromVertices_(settings.punctualLights && settings.bounces >= 2 && !lightAim_.empty()),
      sceneScale_(scene.bounds.isEmpty() ? 1.0f : scene.bounds.diagonal().norm()) {}

float PathIntegrator::rayOffset(const Eigen::Vector3f& point) const { return surfaceRayOffset(point, sceneScale_); }

bool PathIntegrator::makeVertex(const Hit& hit, const Eigen::Vector3f& albedo, const Eigen::Vector3f& origin,
                                const Eigen::Vector3f& direction, const Eigen::Vector3f& throughput,
                                Vertex* vertex) const {
  if (!(albedo.maxCoeff() > 0.0f)) return false;
  const Eigen::Vector3f front = hit.frontNormal * (1.0f / hit.frontNormal.norm());
  const Eigen::Vector3f point = origin + hit.distance * direction;
  vertex->normal = hit.frontFace ? front : Eigen::Vector3f(-front);
  vertex->origin = point + rayOffset(point) * vertex->normal;
  vertex->scatteredThroughput = throughput.cwiseProduct(albedo);
  return true;
}

void PathIntegrator::locateSurfaces(const Hit* hits, int count, SurfacePoint* surfaces) const {
  if (!textured_) return;
  for (int i = 0; i < count; ++i)
    if (!hits[i].missed()) {
      const Hit& hit = hits[i];
      locateSurface(scene_, scene_.instances[hit.instance].mesh, hit.triangle, hit.u, hit.v, &surfaces[i]);
      prefetchSurface(surfaces[i]);
    }
}

const SurfacePoint& PathIntegrator::surfaceAt(const Hit& hit, SurfacePoint* located) const {
  if (!textured_) locateSurface(scene_, scene_.instances[hit.instance].mesh, hit.triangle, hit.u, hit.v, located);
  return *located;
}

void PathIntegrator::trace(const Eigen::Vector3f& position, std::uint64_t probeId, const Eigen::Vector3f* directions,
                           int count, Eigen::Vector3f* radiance, float* visibility, RayCounts* counts,
                           const ProbeView* directView, float* hitDistance, Eigen::Vector3f* skyBounced,
                           FirstReflection* firstReflections, Eigen::Vector3f* reflected,
                           Eigen::Vector3f* reflectedSky) const {
  const Environment& sky = scene_.environment;
  const bool seeSky = settings_.environment && sky.emits();
  thread_local Scratch scratch;
  Vertex* vertices = scratch.vertices.reserve(std::size_t(count));
  const std::uint64_t probeKey = PathRandom::probeKey(settings_.seed, probeId);
  int live = 0;
  Hit hits[8];
  SurfacePoint surfaces[8];
  for (int first = 0; first < count; first += 8) {
    const int n = std::min(8, count - first);
    tracer_.intersect8(position, directions + first, n, hits);
    counts->probe += n;
    locateSurfaces(hits, n, surfaces);
    for (int i = 0; i < n; ++i) {
      const int ray = first + i;
      const Hit& hit = hits[i];
      radiance[ray].setZero();
      if (skyBounced) skyBounced[ray].setZero();
      if (reflected) reflected[ray].setZero();
      if (reflectedSky) reflectedSky[ray].setZero();
      if (firstReflections) firstReflections[ray] = FirstReflection{};
      visibility[ray] = hit.missed() ? 1.0f : 0.0f;
      if (hitDistance) hitDistance[ray] = hit.missed() ? std::numeric_limits<float>::infinity() : hit.distance;
      if (hit.missed()) {
        if (seeSky) {
          radiance[ray] = sky.radiance(directions[ray]);
          if (directView) radiance[ray] *= directView->sampler->latticeSkyWeight(*directView, directions[ray]);
        }
        continue;
      }
      const SurfacePoint& surface = surfaceAt(hit, &surfaces[i]);
      const Material& material = *surface.material;
      if (settings_.emission && (hit.frontFace || material.doubleSided) && material.emissive()) {
        radiance[ray] = surfaceEmission(surface);
        if (directView) radiance[ray] *= directView->sampler->latticeEmitterWeight(*directView, hit, directions[ray]);
      }
      if (settings_.bounces == 0) continue;
      Vertex& v = vertices[live];
      const Eigen::Vector3f albedo = surfaceAlbedo(surface);
      if (makeVertex(hit, albedo, position, directions[ray], Eigen::Vector3f::Ones(), &v)) {
        if (firstReflections) firstReflections[ray] = {v.origin, v.normal, albedo, hit.instance, hit.frontFace, true};
        v.path = ray;
        v.arrivalPdf = 0.0f;
        v.random = PathRandom::fromProbeKey(probeKey, std::uint64_t(ray));
        ++live;
      }
    }
  }
  // The last reflection still needs its continuation ray when emitters or the sky are
  // combined with it by MIS: the ray may find them.
  const bool lastContinuation = sampleEmitters_ || sampleEnvironment_;
  // What the first hit receives after another reflection goes to `reflected` when asked for:
  // the estimates made at the second vertex on, and the aimed rays', which share with them.
  Eigen::Vector3f* beyond = reflected ? reflected : radiance;
  Eigen::Vector3f* skyBeyond = reflected ? reflectedSky : skyBounced;
  for (int bounce = 1; bounce <= settings_.bounces && live > 0; ++bounce) {
    if (bounce == 1)
      addNextEvents(vertices, live, scratch, radiance, skyBounced, counts, directView, directions);
    else
      addNextEvents(vertices, live, scratch, beyond, skyBeyond, counts);
    if (bounce == settings_.bounces && !lastContinuation) break;
    if (aimFromVertices_ && bounce < settings_.bounces) aimAtLights(vertices, live, scratch, beyond, counts);
    // What the continuation finds by MIS (an emitter, the sky) belongs with its vertex's next events.
    live = continuePaths(vertices, live, bounce < settings_.bounces, scratch, bounce == 1 ? radiance : beyond,
                         bounce == 1 ? skyBounced : skyBeyond, counts);
  }
}

// Shadow rays of one kind of next event, traced as one stream once every vertex has made its
// own; each adds its contribution to its path's radiance if nothing blocks it.
struct PathIntegrator::ShadowBatch {
  Ray* rays;
  Scratch::Pending* pending;
  int count = 0;

  // The rays go into `store`: scratch.rays, unless that holds the rays being shaded.
  ShadowBatch(Scratch& scratch, std::size_t most) : ShadowBatch(scratch.rays, scratch, most) {}
  ShadowBatch(ScratchBuffer<Ray>& store, Scratch& scratch, std::size_t most)
      : rays(store.reserve(most)), pending(scratch.pending.reserve(most)) {}
  // `alsoTo`, when given, receives the same contributions (the sky's, kept apart).
  void resolve(const RayTracer& tracer, Scratch& scratch, Eigen::Vector3f* radiance, std::int64_t* counter,
               Eigen::Vector3f* alsoTo = nullptr) const {
    if (count == 0) return;
    bool* blocked = scratch.blocked.reserve(std::size_t(count));
    tracer.occluded(rays, count, blocked);
    for (int k = 0; k < count; ++k)
      if (!blocked[k]) {
        radiance[pending[k].path] += pending[k].contribution;
        if (alsoTo) alsoTo[pending[k].path] += pending[k].contribution;
      }
    *counter += count;
  }
};

void PathIntegrator::addNextEvents(Vertex* vertices, int count, Scratch& scratch, Eigen::Vector3f* radiance,
                                   Eigen::Vector3f* skyBounced, RayCounts* counts, const ProbeView* firstHits,
                                   const Eigen::Vector3f* directions) const {
  if (settings_.punctualLights && !scene_.lights.empty())
    addPunctualEvents(vertices, count, scratch, radiance, counts, firstHits, directions);
  if (sampleEmitters_) addEmitterEvents(vertices, count, scratch, radiance, counts);
  if (sampleEnvironment_) addEnvironmentEvents(vertices, count, scratch, radiance, skyBounced, counts);
}

void PathIntegrator::addPunctualEvents(Vertex* vertices, int count, Scratch& scratch, Eigen::Vector3f* radiance,
                                       RayCounts* counts, const ProbeView* firstHits,
                                       const Eigen::Vector3f* directions) const {
  ShadowBatch batch(scratch, std::size_t(count) * scene_.lights.size());
  for (int k = 0; k < count; ++k) {
    const Vertex& v = vertices[k];
    const Eigen::Vector3f reflect = v.scatteredThroughput * kInvPi;
    // Reached by a continuation from a vertex that also aimed at the lights: the lights'
    // terms here share with that aim.
    const bool aimedFrom = !firstHits && aimFromVertices_ && v.arrivalPdf > 0.0f;
    const double aimTotal = aimedFrom ? v.aimTotal : 0.0;
    for (std::size_t l = 0; l < scene_.lights.size(); ++l) {
      const PunctualLight& light = scene_.lights[l];
      Eigen::Vector3f toLight;
      float distance = std::numeric_limits<float>::infinity();
      Eigen::Vector3f irradiance = light.color * light.intensity;  // on a surface facing the light
      if (light.type == PunctualLight::Type::Directional) {
        toLight = -light.direction;
      } else {
        const Eigen::Vector3f d = light.position - v.origin;
        distance = d.norm();
        if (!(distance > 0.0f)) continue;
        toLight = d / distance;
        irradiance /= distance * distance;
        if (light.type == PunctualLight::Type::Spot) irradiance *= light.spotFalloff(-toLight.dot(light.direction));
      }
      const float cosine = v.normal.dot(toLight);
      // A light almost on the surface can exceed single precision: dropped, as at probes.
      if (cosine <= 0.0f || !(irradiance.maxCoeff() > 0.0f) || !irradiance.allFinite()) continue;
      float share = 1.0f;
      if (light.type != PunctualLight::Type::Directional) {
        if (firstHits)
          share = firstHits->sampler->latticeSpotWeight(*firstHits, int(l), directions[v.path]);
        else if (aimTotal > 0.0) {
          const LightAim::Aim aim = lightAim_.aim(int(l), v.previous);
          share = powerHeuristic(v.arrivalPdf, float(aim.weight / aimTotal) * LightAim::density(aim, v.arrival));
        }
      }
      batch.rays[batch.count] = {v.origin, toLight, 0.0f, distance};
      batch.pending[batch.count++] = {v.path, reflect.cwiseProduct(irradiance) * (cosine * share)};
    }
  }
  batch.resolve(tracer_, scratch, radiance, &counts->punctualShadow);
}

void PathIntegrator::addEmitterEvents(Vertex* vertices, int count, Scratch& scratch, Eigen::Vector3f* radiance,
                                      RayCounts* counts) const {
  // Every vertex's point on an emitter is drawn (and its texels prefetched) before any is
  // shaded, so that the scattered emission lookups wait for memory together.
  ShadowBatch batch(scratch, std::size_t(count));
  Scratch::EmitterPoint* points = scratch.points.reserve(std::size_t(count));
  SurfacePoint* surfaces = scratch.emitterSurfaces.reserve(std::size_t(count));
  // Written as each point is drawn, where the vertex and the emitter are at hand, rather than
  // gathered lane by lane through the vertex and emitter pointers. A short last block repeats its
  // last point in the lanes past it; what they compute is not read.
  const std::size_t padded = std::size_t((count + kLanes - 1) / kLanes * kLanes);
  float* lane = scratch.emitterLanes.reserve(kEmitterLaneArrays * padded);
  float *dxs = lane, *dys = lane + padded, *dzs = lane + 2 * padded, *nxs = lane + 3 * padded,
        *nys = lane + 4 * padded, *nzs = lane + 5 * padded, *fxs = lane + 6 * padded, *fys = lane + 7 * padded,
        *fzs = lane + 8 * padded, *areaDensities = lane + 9 * padded;
  for (int k = 0; k < count; ++k) {
    PathRandom& random = vertices[k].random;
    float xiChoice, xi1, xi2, xiCoverage;
    random.uniformPair(&xiChoice, &xi1);
    random.uniformPair(&xi2, &xiCoverage);
    const EmitterSampler::Sample s = emitters_.sample(xiChoice, xi1, xi2);
    points[k] = {s.emitter, xiCoverage};
    if (s.emitter->textured || s.emitter->alphaTested) {
      locateSurface(scene_, s.emitter->mesh, s.emitter->triangle, s.u, s.v, &surfaces[k]);
      prefetchSurface(surfaces[k]);
    }
    const Vertex& v = vertices[k];
    const EmitterSampler::Emitter& e = *s.emitter;
    dxs[k] = s.point.x() - v.origin.x(), dys[k] = s.point.y() - v.origin.y(), dzs[k] = s.point.z() - v.origin.z();
    nxs[k] = v.normal.x(), nys[k] = v.normal.y(), nzs[k] = v.normal.z();
    fxs[k] = e.frontNormal.x(), fys[k] = e.frontNormal.y(), fzs[k] = e.frontNormal.z();
    areaDensities[k] = e.pdfArea;
  }
  for (std::size_t k = std::size_t(count); k < padded; ++k)
    for (std::size_t a = 0; a < kEmitterLaneArrays; ++a) lane[a * padded + k] = lane[a * padded + std::size_t(count) - 1];
  for (int first = 0; first < count; first += kLanes) {
    const int n = std::min(kLanes, count - first);
    // The geometry of each vertex's shadow ray, in lanes.
    const auto load = [&](const float* values) -> Lanes { return Eigen::Map<const Lanes>(values + first); };
    const Lanes dx = load(dxs), dy = load(dys), dz = load(dzs), nx = load(nxs), ny = load(nys), nz = load(nzs);
    const Lanes fx = load(fxs), fy = load(fys), fz = load(fzs), pdfArea = load(areaDensities);
    // Sums of three terms as Eigen's Vector3f squaredNorm and dot add them (its unrolled
    // reduction splits three as one and two): x + (y + z).
    const Lanes squaredDistance = dx * dx + (dy * dy + dz * dz);
    const Lanes distance = exactSqrt(squaredDistance);
    const Lanes inverse = 1.0f / distance;
    const Lanes tx = dx * inverse, ty = dy * inverse, tz = dz * inverse;
    const Lanes cosine = nx * tx + (ny * ty + nz * tz);
    const Lanes cosLight = -(fx * tx + (fy * ty + fz * tz));
    // The power heuristic's weight over the light's solid-angle pdf, in one division:
    // with pdfLight = a/c (a = pdfArea·r², c = |cosθ_light|) and the BSDF's b = cosθ/π,
    // (pdfLight² / (pdfLight² + b²)) / pdfLight = a·c / (a² + b²·c²).
    const Lanes a = pdfArea * squaredDistance, c = cosLight.abs(), b = cosine * kInvPi;
    const Lanes weightOverPdf = a * c / (a * a + b * b * c * c);
    const Lanes reflected = kInvPi * cosine * weightOverPdf;
    for (int j = 0; j < n; ++j) {
      const int k = first + j;
      const Vertex& v = vertices[k];
      const EmitterSampler::Emitter& e = *points[k].emitter;
      if (!(distance[j] > 0.0f) || cosine[j] <= 0.0f) continue;
      if (std::abs(cosLight[j]) < 1e-6f || (cosLight[j] < 0.0f && !e.doubleSided)) continue;
      if (settings_.alphaFilters && e.alphaTested && !surfaceStopsRay(surfaces[k], points[k].xiCoverage))
        continue;  // a transparent texel
      const Eigen::Vector3f emission = e.textured ? surfaceEmission(surfaces[k]) : e.emission;
      const Eigen::Vector3f contribution = v.scatteredThroughput.cwiseProduct(emission) * reflected[j];
      if (!(contribution.maxCoeff() > 0.0f) || !contribution.allFinite()) continue;
      batch.rays[batch.count] = {v.origin, {tx[j], ty[j], tz[j]}, 0.0f, distance[j] * (1.0f - kShadowShortening)};
      batch.pending[batch.count++] = {v.path, contribution};
    }
  }
  batch.resolve(tracer_, scratch, radiance, &counts->emitterShadow);
}

void PathIntegrator::addEnvironmentEvents(Vertex* vertices, int count, Scratch& scratch, Eigen::Vector3f* radiance,
                                          Eigen::Vector3f* skyBounced, RayCounts* counts) const {
  const Environment& sky = scene_.environment;
  ShadowBatch batch(scratch, std::size_t(count));
  for (int k = 0; k < count; ++k) {
    Vertex& v = vertices[k];
    float xi1, xi2;
    v.random.uniformPair(&xi1, &xi2);
    const Environment::Sample s = sky.sample(xi1, xi2);
    const float cosine = v.normal.dot(s.direction);
    if (!(s.pdf > 0.0f) || cosine <= 0.0f) continue;
    const float weight = powerHeuristic(s.pdf, cosine * kInvPi);
    const Eigen::Vector3f contribution =
        v.scatteredThroughput.cwiseProduct(s.radiance) * (kInvPi * cosine * weight / s.pdf);
    if (!(contribution.maxCoeff() > 0.0f) || !contribution.allFinite()) continue;
    batch.rays[batch.count] = {v.origin, s.direction, 0.0f, std::numeric_limits<float>::infinity()};
    batch.pending[batch.count++] = {v.path, contribution};
  }
  batch.resolve(tracer_, scratch, radiance, &counts->environmentShadow, skyBounced);
}

void PathIntegrator::aimAtLights(Vertex* vertices, int count, Scratch& scratch, Eigen::Vector3f* radiance,
                                 RayCounts* counts) const {
  // Each vertex aims one direction near a light (chosen by power over squared distance), and
  // its first hit takes that light's next-event term, weighted against the continuation's
  // next vertex, whose term addNextEvents weights the other way (power heuristic).
  Ray* rays = scratch.rays.reserve(std::size_t(count));
  Aimed* aimed = scratch.aimed.reserve(std::size_t(count));
  const std::vector<int>& aimable = lightAim_.lights();
  double* weights = scratch.aimWeights.reserve(aimable.size());
  int aimedRays = 0;
  for (int k = 0; k < count; ++k) {
    Vertex& v = vertices[k];
    float xiChoice, xi1;
    v.random.uniformPair(&xiChoice, &xi1);
    const float xi2 = v.random.uniform();
    double total = 0.0;
    for (std::size_t j = 0; j < aimable.size(); ++j) {
      weights[j] = lightAim_.weight(aimable[j], v.origin);
      total += weights[j];
    }
    v.aimTotal = total;
    if (!(total > 0.0)) continue;
    std::size_t j = 0;
    for (double running = weights[0]; j + 1 < aimable.size() && !(xiChoice * total < running);)
      running += weights[++j];
    const int light = aimable[j];
    const LightAim::Aim aim = lightAim_.aim(light, v.origin);
    if (!(aim.width > 0.0f)) continue;
    const Eigen::Vector3f direction = LightAim::direction(aim, xi1, xi2);
    const float cosine = v.normal.dot(direction);
    if (cosine <= 0.0f) continue;
    const float density = float(aim.weight / total) * LightAim::density(aim, direction);
    const float bsdfPdf = cosine * kInvPi;
    // (ρ/π)·cosθ / pdf, times the aim's share.
    const Eigen::Vector3f throughput = v.scatteredThroughput * (bsdfPdf / density * powerHeuristic(density, bsdfPdf));
    if (!(throughput.maxCoeff() > 0.0f) || !throughput.allFinite()) continue;
    rays[aimedRays] = {v.origin, direction, 0.0f, std::numeric_limits<float>::infinity()};
    aimed[aimedRays++] = {v.path, light, throughput};
  }
  shadeAimedHits(rays, aimed, aimedRays, scratch, radiance, counts);
}

void PathIntegrator::shadeAimedHits(const Ray* rays, const Aimed* aimed, int aimedRays, Scratch& scratch,
                                    Eigen::Vector3f* radiance, RayCounts* counts) const {
  ShadowBatch batch(scratch.shadowRays, scratch, std::size_t(aimedRays));
  Hit hits[8];
  SurfacePoint surfaces[8];
  for (int first = 0; first < aimedRays; first += 8) {
    const int n = std::min(8, aimedRays - first);
    tracer_.intersect8(rays + first, n, hits);
    counts->aimedBounce += n;
    locateSurfaces(hits, n, surfaces);
    for (int i = 0; i < n; ++i) {
      const Hit& hit = hits[i];
      if (hit.missed()) continue;
      const Ray& ray = rays[first + i];
      const Aimed& a = aimed[first + i];
      const SurfacePoint& surface = surfaceAt(hit, &surfaces[i]);
      const Eigen::Vector3f albedo = surfaceAlbedo(surface);
      if (!(albedo.maxCoeff() > 0.0f)) continue;
      const Eigen::Vector3f front = hit.frontNormal * (1.0f / hit.frontNormal.norm());
      const Eigen::Vector3f normal = hit.frontFace ? front : Eigen::Vector3f(-front);
      const Eigen::Vector3f point = ray.origin + hit.distance * ray.direction;
      const Eigen::Vector3f origin = point + rayOffset(point) * normal;
      const PunctualLight& light = scene_.lights[a.light];
      const Eigen::Vector3f d = light.position - origin;
      const float distance = d.norm();
      if (!(distance > 0.0f)) continue;
      const Eigen::Vector3f toLight = d / distance;
      const float cosine = normal.dot(toLight);
      if (cosine <= 0.0f) continue;
      Eigen::Vector3f irradiance = light.color * (light.intensity / (distance * distance));
      if (light.type == PunctualLight::Type::Spot) irradiance *= light.spotFalloff(-toLight.dot(light.direction));
      const Eigen::Vector3f contribution = a.throughput.cwiseProduct(albedo).cwiseProduct(irradiance) * (cosine * kInvPi);
      if (!(contribution.maxCoeff() > 0.0f) || !contribution.allFinite()) continue;
      batch.rays[batch.count] = {origin, toLight, 0.0f, distance};
      batch.pending[batch.count++] = {a.path, contribution};
    }
  }
  batch.resolve(tracer_, scratch, radiance, &counts->aimedBounceShadow);
}

int PathIntegrator::sampleContinuations(Vertex* vertices, int count, Ray* rays, float* bsdfPdf, int* sources) const {
  // The rays of the paths that go on are compacted to the front, each naming the vertex it
  // leaves, in order: continuePaths writes the vertex ray i makes at index i or before, over one
  // it has read or one no ray leaves. The vertices stay where they are (moved along with their
  // rays, they were copied field by field).
  int survivors = 0;
  for (int first = 0; first < count; first += kLanes) {
    const int n = std::min(kLanes, count - first);
    // Lanes past the last path get constants, not a copy of it: filling a lane draws the path's
    // random numbers. Their directions are not read.
    Lanes nx = Lanes::Zero(), ny = Lanes::Zero(), nz = Lanes::Ones();
    Lanes xi1 = Lanes::Zero(), xi2 = Lanes::Zero();
    for (int j = 0; j < n; ++j) {
      Vertex& v = vertices[first + j];
      nx[j] = v.normal.x(), ny[j] = v.normal.y(), nz[j] = v.normal.z();
      v.random.uniformPair(&xi1[j], &xi2[j]);
    }
    const CosineDirections directions = cosineDirections(nx, ny, nz, xi1, xi2);
    for (int j = 0; j < n; ++j) {
      const int k = first + j;
      Vertex& v = vertices[k];
      const float weight = v.scatteredThroughput.maxCoeff();
      if (weight < kRouletteThreshold) {
        const float survival = weight / kRouletteThreshold;
        if (v.random.uniform() >= survival) continue;
        v.scatteredThroughput /= survival;
      }
      rays[survivors] = {v.origin, {directions.x[j], directions.y[j], directions.z[j]}, 0.0f,
                         std::numeric_limits<float>::infinity()};
      bsdfPdf[survivors] = directions.cosine[j] * kInvPi;
      sources[survivors] = k;
      ++survivors;
    }
  }

  return survivors;
}

int PathIntegrator::continuePaths(Vertex* vertices, int count, bool keepVertices, Scratch& scratch,
                                  Eigen::Vector3f* radiance, Eigen::Vector3f* skyBounced, RayCounts* counts) const {
  Ray* rays = scratch.rays.reserve(std::size_t(count));
  float* bsdfPdf = scratch.pdfs.reserve(std::size_t(count));
  int* sources = scratch.sources.reserve(std::size_t(count));
  const int survivors = sampleContinuations(vertices, count, rays, bsdfPdf, sources);
  const Environment& sky = scene_.environment;
  Hit hits[8];
  SurfacePoint surfaces[8];
  int kept = 0;
  for (int first = 0; first < survivors; first += 8) {
    const int n = std::min(8, survivors - first);
    tracer_.intersect8(rays + first, n, hits);
    counts->bounce += n;
    if (sampleEmitters_ || keepVertices) locateSurfaces(hits, n, surfaces);
    for (int i = 0; i < n; ++i) {
      // What the next vertex needs of this one, copied: it may take this one's place.
      const Vertex& from = vertices[sources[first + i]];
      const Eigen::Vector3f throughput = from.scatteredThroughput;
      const int path = from.path;
      const PathRandom random = from.random;
      const double aimTotal = from.aimTotal;
      const Ray& ray = rays[first + i];
      const float pdf = bsdfPdf[first + i];
      const Hit& hit = hits[i];
      if (hit.missed()) {
        if (sampleEnvironment_) {
          const float weight = powerHeuristic(pdf, sky.pdf(ray.direction));
          const Eigen::Vector3f skyLight = throughput.cwiseProduct(sky.radiance(ray.direction)) * weight;
          radiance[path] += skyLight;
          if (skyBounced) skyBounced[path] += skyLight;
        }
        continue;
      }
      if (!sampleEmitters_ && !keepVertices) continue;
      const SurfacePoint& surface = surfaceAt(hit, &surfaces[i]);
      const Material& material = *surface.material;
      if (sampleEmitters_ && (hit.frontFace || material.doubleSided) && material.emissive()) {
        const Eigen::Vector3f emission = surfaceEmission(surface);
        if (emission.maxCoeff() > 0.0f) {
          const float cosLight = std::abs(hit.frontNormal.normalized().dot(ray.direction));
          const float pdfLight =
              cosLight > 0.0f ? emitters_.pdfArea(hit.instance, hit.triangle) * hit.distance * hit.distance / cosLight
                              : 0.0f;
          radiance[path] += throughput.cwiseProduct(emission) * powerHeuristic(pdf, pdfLight);
        }
      }
      Vertex& next = vertices[kept];
      if (keepVertices && makeVertex(hit, surfaceAlbedo(surface), ray.origin, ray.direction, throughput, &next)) {
        next.path = path;
        next.random = random;
        next.previous = ray.origin;
        next.arrival = ray.direction;
        next.arrivalPdf = pdf;
        next.aimTotal = aimTotal;
        ++kept;
      }
    }
  }
  return kept;
}

}  // namespace baker
