#pragma once
#include <cstdint>

#include "bake/Basis.h"
#include "bake/GramOperators.h"
#include "bake/ProbeGrid.h"
#include "bake/Volume.h"
#include "scene/RayTracer.h"
#include "scene/Scene.h"

namespace baker {

// Probes are baked in bricks of kBrickSize³: the unit of parallel work and an OpenVDB leaf.
constexpr int kBrickSize = 8;

struct BakeStats {
  std::int64_t probes = 0;
  std::int64_t bricks = 0;
  int raysPerProbe = 0;
  std::int64_t raysTraced = 0;
  double conditionNumber = 0.0;  // worst of the basis's Gram matrices
  int shOrder = 0;               // SH order the samples are fitted with on their way to the basis
  double operatorSeconds = 0.0;  // building the projection operators
  double traceSeconds = 0.0;     // tracing and projecting every brick
};

// How ray samples become coefficients beyond the default linear projection.
struct ProjectionOptions {
  BandWindow window;         // Hann window on the SH bands (paper eq. 8) against ringing
  bool nonNegative = false;  // coefficients ≥ 0 by a per-probe constrained solve (NonNegativeProjection)
};

// Traces `rays` spherical Fibonacci directions from every probe of `grid` and projects the
// irradiance they imply (E(n) = ∫ L max(0, n·ω) dω, full irradiance, not E/π) into `basis`:
// one matrix product per brick and channel group. The result does not depend on the number of
// threads.
Volume bakeVolume(const Scene& scene, const RayTracer& tracer, const Basis& basis, const ProbeGrid& grid, int rays,
                  BakeStats* stats, const ProjectionOptions& options = {});

}  // namespace baker
