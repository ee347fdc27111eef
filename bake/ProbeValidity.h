#pragma once
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "scene/RayTracer.h"
#include "volume/ProbeGrid.h"
#include "volume/ProbeState.h"

namespace baker {

// Probe validity: a probe inside geometry sees the back faces of the surfaces around it and
// would bake their darkness into every cell it touches.
//
// The test: a probe traces a fixed spherical Fibonacci set of rays; its back-face ratio is the
// fraction that hit a back face (the side opposite glTF's counter-clockwise front, whatever the
// material's doubleSided says: rooms are modelled with their normals facing inward, so an open
// room reads 0 and the inside of a solid reads close to 1). Rays that miss count as not back.
// A ratio above maxBackfaceRatio means the probe is inside geometry. The rays start a few float
// steps behind the probe, so that a probe exactly on a surface (a floor, an edge) meets its
// back face at distance 0 on half its rays, instead of seeing through it: it reads as inside
// and is moved off to the front side like any other.
//
// The move: such a probe is moved through the nearest back face by at most maxOffsetFraction
// (0.45) of the spacing, so it stays inside its own cell. The candidates are its back-face hits,
// nearest first; each puts the probe a small margin beyond the hit along that ray, provided
// nothing else lies within that margin, and is accepted if the probe passes the test there.
// Only the nearest few candidates are tried, which bounds the cost. A probe with no acceptable
// candidate is Invalid, and fillInvalidProbes (volume/InvalidProbeFill.h) gives it the mean of its valid neighbours.
struct ProbePlacement {
  Eigen::Vector3f offset{0.0f, 0.0f, 0.0f};  // world-space move from the grid position; zero unless Relocated
  ProbeState state = ProbeState::Valid;
  float backfaceRatio = 0.0f;  // at the grid position
};

struct ValidityOptions {
  float maxBackfaceRatio = 0.25f;   // a probe whose rays hit more back faces than this is inside geometry
  float maxOffsetFraction = 0.45f;  // of the spacing: a relocated probe stays inside its own cell
  int rays = 64;                    // spherical Fibonacci directions per test
};

// The fixed unit directions of the test: options.rays spherical Fibonacci points.
std::vector<Eigen::Vector3f> validityDirections(const ValidityOptions& options);

// Tests the probe at gridPosition and, when it is inside geometry, tries to move it out.
// Adds the rays it traced (closest-hit and occlusion) to *raysTraced unless that is null.
ProbePlacement placeProbe(const RayTracer& tracer, const Eigen::Vector3f& gridPosition, float spacing,
                          const std::vector<Eigen::Vector3f>& directions, const ValidityOptions& options,
                          std::int64_t* raysTraced);

}  // namespace baker
