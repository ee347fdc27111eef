#pragma once
#include <Eigen/Core>
#include <cstdint>

#include "scene/Scene.h"

namespace baker {

// The surface at one point of a triangle, in linear RGB.
struct SurfaceSample {
  Eigen::Vector3f albedo{1.0f, 1.0f, 1.0f};     // baseColorFactor × baseColorTexture × COLOR_0
  Eigen::Vector3f emission{0.0f, 0.0f, 0.0f};   // emissive factor × strength × emissiveTexture
  float alpha = 1.0f;                           // coverage: the same product's alpha (1 for OPAQUE)
  bool doubleSided = false;                     // single-sided surfaces emit from the front only
};

// Shades triangle `triangle` of `mesh` at the barycentric weights Embree reports (as in
// locateSurface below).
SurfaceSample shadeSurface(const Scene& scene, std::uint32_t mesh, std::uint32_t triangle, float u, float v);

// A point of a triangle, located once for the lookups a path makes there: its material and
// corners, and where each of its textures will be read. Locating a batch of points, prefetching
// their texels, and only then reading them overlaps the batch's cache misses.
struct SurfacePoint {
  const Mesh* mesh = nullptr;
  const Material* material = nullptr;
  const Eigen::Vector3i* corners = nullptr;
  float w0 = 1.0f, w1 = 0.0f, w2 = 0.0f;       // barycentric weights of the three corners
  const ColorImage* baseColorImage = nullptr;  // null: no texture, the factor alone
  const ColorImage* emissiveImage = nullptr;   // null also when the material does not emit
  ColorImage::Footprint baseColorTexels, emissiveTexels;
};

// The out-of-line parts of locateSurface and surfaceAlbedo below: where a point's textures are
// read, and its albedo when a texture or vertex colours vary it.
void locateTexels(SurfacePoint* point);
Eigen::Vector3f variedAlbedo(const SurfacePoint& point);

// Triangle `triangle` of `mesh` at the barycentric weights Embree reports: u for the
// triangle's second corner, v for its third. Written in place, and only the texels of textures
// the material has: a bake locates every hit, most often in untextured scenes, and a point
// returned whole was copied through memory again. Inline, as is surfaceAlbedo: in an untextured
// scene each is a few loads, and a call from another file cost as much again.
inline void locateSurface(const Scene& scene, std::uint32_t mesh, std::uint32_t triangle, float u, float v,
                          SurfacePoint* point) {
  SurfacePoint& p = *point;
  p.mesh = &scene.meshes[mesh];
  p.material = &scene.materials[p.mesh->triangleMaterial[triangle]];
  p.corners = &p.mesh->triangles[triangle];
  p.w0 = 1.0f - u - v;
  p.w1 = u;
  p.w2 = v;
  const Material& m = *p.material;
  p.baseColorImage = m.baseColorTexture.present() ? &scene.images[m.baseColorTexture.image] : nullptr;
  p.emissiveImage = m.emissiveTexture.present() && m.emissive() ? &scene.images[m.emissiveTexture.image] : nullptr;
  if (p.baseColorImage || p.emissiveImage) locateTexels(&p);
}

// Starts loading the texels a point's lookups will read, without waiting for them.
void prefetchSurface(const SurfacePoint& point);
// The albedo and the emission at a point on their own: each is a texture lookup, and a random
// one costs a cache miss, so a path reads only the one it needs at each point.
inline Eigen::Vector3f surfaceAlbedo(const SurfacePoint& point) {
  if (!point.baseColorImage && point.mesh->colors.empty()) return point.material->baseColor.head<3>();
  return variedAlbedo(point);
}
Eigen::Vector3f surfaceEmission(const SurfacePoint& point);

// Whether an alpha-tested surface stops a ray there. MASK: alpha ≥ alphaCutoff, as the glTF
// spec says. BLEND: stochastic coverage, opaque when xi < alpha, so that the fraction of rays a
// BLEND surface stops is its alpha (the reference renderer does the same); `xi` is a uniform
// number in [0, 1) the caller derives deterministically from the ray. OPAQUE always stops.
bool surfaceStopsRay(const SurfacePoint& point, float xi);
bool surfaceStopsRay(const Scene& scene, std::uint32_t mesh, std::uint32_t triangle, float u, float v, float xi);

}  // namespace baker
