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

// Shades triangle `triangle` of `mesh` at the barycentric weights Embree reports: u for the
// triangle's second corner, v for its third.
SurfaceSample shadeSurface(const Scene& scene, std::uint32_t mesh, std::uint32_t triangle, float u, float v);

// The albedo and the emission of shadeSurface on their own: each is a texture lookup, and a
// random one costs a cache miss, so a path reads only the one it needs at each point.
Eigen::Vector3f surfaceAlbedo(const Scene& scene, std::uint32_t mesh, std::uint32_t triangle, float u, float v);
Eigen::Vector3f surfaceEmission(const Scene& scene, std::uint32_t mesh, std::uint32_t triangle, float u, float v);

// Starts loading the texels those lookups will read at that point, without waiting for them:
// shading a batch of points after prefetching each overlaps their cache misses.
void prefetchSurface(const Scene& scene, std::uint32_t mesh, std::uint32_t triangle, float u, float v);

// Whether an alpha-tested surface stops a ray there. MASK: alpha ≥ alphaCutoff, as the glTF
// spec says. BLEND: stochastic coverage, opaque when xi < alpha, so that the fraction of rays a
// BLEND surface stops is its alpha (the reference renderer does the same); `xi` is a uniform
// number in [0, 1) the caller derives deterministically from the ray. OPAQUE always stops.
bool surfaceStopsRay(const Scene& scene, std::uint32_t mesh, std::uint32_t triangle, float u, float v, float xi);

}  // namespace baker
