#include "bake/PathIntegrator.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "bake/PathRandom.h"
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

float powerHeuristic(float pdf, float otherPdf) {
  const float a = pdf * pdf, b = otherPdf * otherPdf;
  return a + b > 0.0f ? a / (a + b) : 0.0f;
}

// A cosine-distributed direction about `normal` (pdf cosθ/π), through an orthonormal frame
// that has no singularity (Duff et al. 2017).
Eigen::Vector3f cosineDirection(const Eigen::Vector3f& normal, float xi1, float xi2) {
  const float sign = std::copysign(1.0f, normal.z());
  const float a = -1.0f / (sign + normal.z());
  const float b = normal.x() * normal.y() * a;
  const Eigen::Vector3f t(1.0f + sign * normal.x() * normal.x() * a, sign * b, -sign * normal.x());
  const Eigen::Vector3f s(b, sign + normal.y() * normal.y() * a, -normal.y());
  const float r = std::sqrt(xi1), phi = 2.0f * kPi * xi2;
  return (r * std::cos(phi) * t + r * std::sin(phi) * s + std::sqrt(std::max(0.0f, 1.0f - xi1)) * normal)
      .normalized();
}

}  // namespace

struct PathIntegrator::Vertex {
  Eigen::Vector3f origin;  // where its rays start: the hit point, offset along the normal
  Eigen::Vector3f normal;  // geometric, unit, on the side the path arrived from
  Eigen::Vector3f albedo;
  Eigen::Vector3f throughput;
  int path = 0;
  PathRandom random{0, 0, 0};
};

PathIntegrator::PathIntegrator(const Scene& scene, const RayTracer& tracer, const TransportSettings& settings)
    : scene_(scene),
      tracer_(tracer),
      settings_(settings),
      emitters_(scene),
      sampleEmitters_(settings.emissiveLights && !emitters_.empty()),
      sampleEnvironment_(settings.environment && scene.environment.emits()),
      sceneScale_(scene.bounds.isEmpty() ? 1.0f : scene.bounds.diagonal().norm()) {}

float PathIntegrator::rayOffset(const Eigen::Vector3f& point) const {
  // A hit point is only known to a few units in the last place of its largest coordinate (and
  // of the scene's size, for points near the origin): step 32 of those off the surface.
  const float magnitude = std::max(point.cwiseAbs().maxCoeff(), sceneScale_);
  return 32.0f * (std::nextafter(magnitude, std::numeric_limits<float>::infinity()) - magnitude);
}

bool PathIntegrator::makeVertex(const Hit& hit, const Eigen::Vector3f& albedo, const Eigen::Vector3f& origin,
                                const Eigen::Vector3f& direction, const Eigen::Vector3f& throughput,
                                Vertex* vertex) const {
  if (!(albedo.maxCoeff() > 0.0f)) return false;
  const Eigen::Vector3f front = hit.frontNormal.normalized();
  const Eigen::Vector3f point = origin + hit.distance * direction;
  vertex->normal = hit.frontFace ? front : Eigen::Vector3f(-front);
  vertex->origin = point + rayOffset(point) * vertex->normal;
  vertex->albedo = albedo;
  vertex->throughput = throughput;
  return true;
}

void PathIntegrator::prefetchTextures(const Hit* hits, int count) const {
  if (scene_.images.empty()) return;
  for (int i = 0; i < count; ++i)
    if (!hits[i].missed())
      prefetchSurface(scene_, scene_.instances[hits[i].instance].mesh, hits[i].triangle, hits[i].u, hits[i].v);
}

void PathIntegrator::trace(const Eigen::Vector3f& position, std::uint64_t probeId, const Eigen::Vector3f* directions,
                           int count, Eigen::Vector3f* radiance, float* visibility, RayCounts* counts) const {
  const Environment& sky = scene_.environment;
  const bool seeSky = settings_.environment && sky.emits();
  // Scratch space reused from probe to probe on each thread: a bake traces millions of short
  // wavefronts, and allocating their arrays each time costs as much as shading them.
  thread_local std::vector<Vertex> vertices;
  vertices.clear();
  Hit hits[8];
  for (int first = 0; first < count; first += 8) {
    const int n = std::min(8, count - first);
    tracer_.intersect8(position, directions + first, n, hits);
    counts->probe += n;
    prefetchTextures(hits, n);
    for (int i = 0; i < n; ++i) {
      const int ray = first + i;
      const Hit& hit = hits[i];
      radiance[ray].setZero();
      visibility[ray] = hit.missed() ? 1.0f : 0.0f;
      if (hit.missed()) {
        if (seeSky) radiance[ray] = sky.radiance(directions[ray]);
        continue;
      }
      const std::uint32_t mesh = scene_.instances[hit.instance].mesh;
      const Material& material = scene_.material(hit.instance, hit.triangle);
      if (settings_.emission && (hit.frontFace || material.doubleSided) && material.emissive())
        radiance[ray] = surfaceEmission(scene_, mesh, hit.triangle, hit.u, hit.v);
      Vertex v;
      if (settings_.bounces > 0 && makeVertex(hit, surfaceAlbedo(scene_, mesh, hit.triangle, hit.u, hit.v), position,
                                              directions[ray], Eigen::Vector3f::Ones(), &v)) {
        v.path = ray;
        v.random = PathRandom(settings_.seed, probeId, std::uint64_t(ray));
        vertices.push_back(v);
      }
    }
  }
  // The last reflection still needs its continuation ray when emitters or the sky are
  // combined with it by MIS: the ray may find them.
  const bool lastContinuation = sampleEmitters_ || sampleEnvironment_;
  for (int bounce = 1; bounce <= settings_.bounces && !vertices.empty(); ++bounce) {
    addNextEvents(vertices, radiance, counts);
    if (bounce == settings_.bounces && !lastContinuation) break;
    continuePaths(vertices, bounce < settings_.bounces, radiance, counts);
  }
}

void PathIntegrator::addNextEvents(std::vector<Vertex>& vertices, Eigen::Vector3f* radiance,
                                   RayCounts* counts) const {
  struct Pending {
    int path;
    Eigen::Vector3f contribution;
  };
  thread_local std::vector<Ray> rays;
  thread_local std::vector<Pending> pending;
  thread_local std::unique_ptr<bool[]> blocked;
  thread_local std::size_t blockedCapacity = 0;
  rays.clear();
  pending.clear();
  auto resolve = [&](std::int64_t* counter) {
    if (rays.empty()) return;
    if (blockedCapacity < rays.size()) {
      blockedCapacity = 2 * rays.size();
      blocked.reset(new bool[blockedCapacity]);
    }
    tracer_.occluded(rays.data(), int(rays.size()), blocked.get());
    for (std::size_t k = 0; k < rays.size(); ++k)
      if (!blocked[k]) radiance[pending[k].path] += pending[k].contribution;
    *counter += std::int64_t(rays.size());
    rays.clear();
    pending.clear();
  };

  if (settings_.punctualLights && !scene_.lights.empty()) {
    for (const Vertex& v : vertices) {
      const Eigen::Vector3f reflect = v.throughput.cwiseProduct(v.albedo) * kInvPi;
      for (const PunctualLight& light : scene_.lights) {
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
        rays.push_back({v.origin, toLight, 0.0f, distance});
        pending.push_back({v.path, reflect.cwiseProduct(irradiance) * cosine});
      }
    }
    resolve(&counts->punctualShadow);
  }

  if (sampleEmitters_) {
    // Every vertex's point on an emitter is drawn (and its texels prefetched) before any is
    // shaded, so that the scattered emission lookups wait for memory together.
    struct EmitterPoint {
      const Vertex* vertex;
      EmitterSampler::Sample sample;
      float xiCoverage;
    };
    thread_local std::vector<EmitterPoint> points;
    points.clear();
    for (Vertex& v : vertices) {
      const float xiChoice = v.random.uniform(), xi1 = v.random.uniform(), xi2 = v.random.uniform();
      const float xiCoverage = v.random.uniform();
      const EmitterSampler::Sample s = emitters_.sample(xiChoice, xi1, xi2);
      if (!scene_.images.empty()) prefetchSurface(scene_, scene_.instances[s.instance].mesh, s.triangle, s.u, s.v);
      points.push_back({&v, s, xiCoverage});
    }
    for (const EmitterPoint& point : points) {
      const Vertex& v = *point.vertex;
      const EmitterSampler::Sample& s = point.sample;
      const float xiCoverage = point.xiCoverage;
      const Eigen::Vector3f d = s.point - v.origin;
      const float distance = d.norm();
      if (!(distance > 0.0f)) continue;
      const Eigen::Vector3f toLight = d / distance;
      const float cosine = v.normal.dot(toLight);
      if (cosine <= 0.0f) continue;
      const float cosLight = -s.frontNormal.dot(toLight);
      if (std::abs(cosLight) < 1e-6f || (cosLight < 0.0f && !s.doubleSided)) continue;
      const std::uint32_t mesh = scene_.instances[s.instance].mesh;
      if (settings_.alphaFilters && !surfaceStopsRay(scene_, mesh, s.triangle, s.u, s.v, xiCoverage))
        continue;  // a transparent texel
      const float pdfLight = s.pdfArea * distance * distance / std::abs(cosLight);
      const float weight = powerHeuristic(pdfLight, cosine * kInvPi);
      const Eigen::Vector3f contribution = v.throughput.cwiseProduct(v.albedo).cwiseProduct(
                                               surfaceEmission(scene_, mesh, s.triangle, s.u, s.v)) *
                                           (kInvPi * cosine * weight / pdfLight);
      if (!(contribution.maxCoeff() > 0.0f) || !contribution.allFinite()) continue;
      rays.push_back({v.origin, toLight, 0.0f, distance * (1.0f - kShadowShortening)});
      pending.push_back({v.path, contribution});
    }
    resolve(&counts->emitterShadow);
  }

  if (sampleEnvironment_) {
    const Environment& sky = scene_.environment;
    for (Vertex& v : vertices) {
      const float xi1 = v.random.uniform(), xi2 = v.random.uniform();
      const Environment::Sample s = sky.sample(xi1, xi2);
      const float cosine = v.normal.dot(s.direction);
      if (!(s.pdf > 0.0f) || cosine <= 0.0f) continue;
      const float weight = powerHeuristic(s.pdf, cosine * kInvPi);
      const Eigen::Vector3f contribution =
          v.throughput.cwiseProduct(v.albedo).cwiseProduct(s.radiance) * (kInvPi * cosine * weight / s.pdf);
      if (!(contribution.maxCoeff() > 0.0f) || !contribution.allFinite()) continue;
      rays.push_back({v.origin, s.direction, 0.0f, std::numeric_limits<float>::infinity()});
      pending.push_back({v.path, contribution});
    }
    resolve(&counts->environmentShadow);
  }
}

void PathIntegrator::continuePaths(std::vector<Vertex>& vertices, bool keepVertices, Eigen::Vector3f* radiance,
                                   RayCounts* counts) const {
  thread_local std::vector<Ray> rays;
  thread_local std::vector<float> bsdfPdf;
  rays.clear();
  bsdfPdf.clear();
  // The paths that go on are compacted in place (vertex k traces rays[k]), and so are the
  // vertices their rays make: a vertex is written only over one already read.
  std::size_t survivors = 0;
  for (Vertex& v : vertices) {
    const float xi1 = v.random.uniform(), xi2 = v.random.uniform();
    const Eigen::Vector3f direction = cosineDirection(v.normal, xi1, xi2);
    const float cosine = v.normal.dot(direction);
    if (!(cosine > 0.0f)) continue;
    v.throughput = v.throughput.cwiseProduct(v.albedo);  // (ρ/π)·cosθ over the pdf cosθ/π
    const float weight = v.throughput.maxCoeff();
    if (weight < kRouletteThreshold) {
      const float survival = weight / kRouletteThreshold;
      if (v.random.uniform() >= survival) continue;
      v.throughput /= survival;
    }
    rays.push_back({v.origin, direction, 0.0f, std::numeric_limits<float>::infinity()});
    bsdfPdf.push_back(cosine * kInvPi);
    vertices[survivors++] = v;
  }

  const Environment& sky = scene_.environment;
  Hit hits[8];
  std::size_t kept = 0;
  for (std::size_t first = 0; first < rays.size(); first += 8) {
    const int n = int(std::min<std::size_t>(8, rays.size() - first));
    tracer_.intersect8(rays.data() + first, n, hits);
    counts->bounce += n;
    if (sampleEmitters_ || keepVertices) prefetchTextures(hits, n);
    for (int i = 0; i < n; ++i) {
      const Vertex from = vertices[first + i];  // a copy: the next vertex may take its place
      const Ray& ray = rays[first + i];
      const float pdf = bsdfPdf[first + i];
      const Hit& hit = hits[i];
      if (hit.missed()) {
        if (sampleEnvironment_) {
          const float weight = powerHeuristic(pdf, sky.pdf(ray.direction));
          radiance[from.path] += from.throughput.cwiseProduct(sky.radiance(ray.direction)) * weight;
        }
        continue;
      }
      if (!sampleEmitters_ && !keepVertices) continue;
      const std::uint32_t mesh = scene_.instances[hit.instance].mesh;
      const Material& material = scene_.material(hit.instance, hit.triangle);
      if (sampleEmitters_ && (hit.frontFace || material.doubleSided) && material.emissive()) {
        const Eigen::Vector3f emission = surfaceEmission(scene_, mesh, hit.triangle, hit.u, hit.v);
        if (emission.maxCoeff() > 0.0f) {
          const float cosLight = std::abs(hit.frontNormal.normalized().dot(ray.direction));
          const float pdfLight =
              cosLight > 0.0f ? emitters_.pdfArea(hit.instance, hit.triangle) * hit.distance * hit.distance / cosLight
                              : 0.0f;
          radiance[from.path] += from.throughput.cwiseProduct(emission) * powerHeuristic(pdf, pdfLight);
        }
      }
      Vertex& next = vertices[kept];
      if (keepVertices && makeVertex(hit, surfaceAlbedo(scene_, mesh, hit.triangle, hit.u, hit.v), ray.origin,
                                     ray.direction, from.throughput, &next)) {
        next.path = from.path;
        next.random = from.random;
        ++kept;
      }
    }
  }
  vertices.resize(kept);
}

}  // namespace baker
