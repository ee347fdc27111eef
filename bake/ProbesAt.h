#pragma once
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "bake/ProbeBaker.h"
#include "bake/ProbeValidity.h"

namespace baker {

// Probes baked one by one rather than as a grid: where each was placed, what its rays brought
// back, and its coefficients (coefficientsPerProbe each) and sky visibility.
struct BakedProbes {
  std::vector<ProbePlacement> placements;
  std::vector<ProbeTask> tasks;  // where each was traced, and the id its random numbers derive from
  std::vector<ProbeSamples> samples;
  std::vector<float> coefficients, visibility;
  int coefficientsPerProbe = 0, visibilityPerProbe = 0;
  RayCounts rays;

  const float* probe(std::size_t i) const { return coefficients.data() + i * coefficientsPerProbe; }
  const float* probeVisibility(std::size_t i) const { return visibility.data() + i * visibilityPerProbe; }
};

// Where probes at these positions go: each moved out of geometry as the grid's are
// (ProbeValidity, for a grid of `spacing`) when the transport simulates probe validity, left
// where it is otherwise. Adds the rays the tests traced to *validityRays when given.
std::vector<ProbePlacement> placeProbes(const RayTracer& tracer, const TransportSettings& transport, double spacing,
                                        const std::vector<Eigen::Vector3f>& positions, std::int64_t* validityRays);

// Tasks for probes traced beside others that share their reflections: placed as placeProbes
// does, those inside geometry left out, ids from firstId on, rotation 0.
std::vector<ProbeTask> neighbourTasks(const RayTracer& tracer, const TransportSettings& transport, double spacing,
                                      const std::vector<Eigen::Vector3f>& neighbours, std::uint64_t firstId,
                                      std::int64_t* validityRays);

// Bakes each task (rotation, id and position as given) and keeps its samples. NumericalError
// when a coefficient is not finite.
BakedProbes bakeTasks(const Scene& scene, const RayTracer& tracer, const Basis& basis, const BakeSettings& settings,
                      std::vector<ProbeTask> tasks);

// placeProbes, then bakeTasks: probe i traced from where it was placed (an invalid one where it
// stands), with id i and rotation 0. `neighbours` are placed and traced with them (ids from
// positions.size() on; invalid ones left out) and not returned: with shared reflections, the
// probes whose paths they share.
BakedProbes bakeProbesAt(const Scene& scene, const RayTracer& tracer, const Basis& basis, const BakeSettings& settings,
                         double spacing, const std::vector<Eigen::Vector3f>& positions,
                         const std::vector<Eigen::Vector3f>& neighbours = {});

}  // namespace baker
