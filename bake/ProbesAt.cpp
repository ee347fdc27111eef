#include "bake/ProbesAt.h"

#include <cmath>

#include "common/Error.h"

namespace baker {

std::vector<ProbePlacement> placeProbes(const RayTracer& tracer, const TransportSettings& transport, double spacing,
                                        const std::vector<Eigen::Vector3f>& positions, std::int64_t* validityRays) {
  std::vector<ProbePlacement> placements(positions.size());
  if (!transport.probeValidity) return placements;
  const ValidityOptions options;
  const std::vector<Eigen::Vector3f> testDirections = validityDirections(options);
  for (std::size_t i = 0; i < positions.size(); ++i)
    placements[i] = placeProbe(tracer, positions[i], float(spacing), testDirections, options, validityRays);
  return placements;
}

BakedProbes bakeTasks(const Scene& scene, const RayTracer& tracer, const Basis& basis, const BakeSettings& settings,
                      std::vector<ProbeTask> tasks) {
  const ProbeBaker probeBaker(scene, tracer, basis, settings, 1);
  BakedProbes baked;
  baked.tasks = std::move(tasks);
  baked.coefficientsPerProbe = probeBaker.coefficientsPerProbe();
  baked.visibilityPerProbe = probeBaker.visibilityPerProbe();
  baked.coefficients.resize(baked.tasks.size() * baked.coefficientsPerProbe);
  baked.visibility.resize(baked.tasks.size() * baked.visibilityPerProbe);
  probeBaker.bake(baked.tasks, baked.coefficients.data(), baked.visibility.data(), &baked.rays, &baked.samples);
  for (float c : baked.coefficients)
    if (!std::isfinite(c)) throw NumericalError("a probe's coefficients are not finite: the scene's radiance overflows float");
  return baked;
}

std::vector<ProbeTask> neighbourTasks(const RayTracer& tracer, const TransportSettings& transport, double spacing,
                                      const std::vector<Eigen::Vector3f>& neighbours, std::uint64_t firstId,
                                      std::int64_t* validityRays) {
  const std::vector<ProbePlacement> placed = placeProbes(tracer, transport, spacing, neighbours, validityRays);
  std::vector<ProbeTask> tasks;
  for (std::size_t i = 0; i < neighbours.size(); ++i)
    if (placed[i].state != ProbeState::Invalid) tasks.push_back({neighbours[i] + placed[i].offset, firstId + i, 0});
  return tasks;
}

BakedProbes bakeProbesAt(const Scene& scene, const RayTracer& tracer, const Basis& basis, const BakeSettings& settings,
                         double spacing, const std::vector<Eigen::Vector3f>& positions,
                         const std::vector<Eigen::Vector3f>& neighbours) {
  std::int64_t validityRays = 0;
  std::vector<ProbePlacement> placements = placeProbes(tracer, settings.transport, spacing, positions, &validityRays);
  std::vector<ProbeTask> tasks;
  for (std::size_t i = 0; i < positions.size(); ++i) tasks.push_back({positions[i] + placements[i].offset, i, 0});
  for (const ProbeTask& task : neighbourTasks(tracer, settings.transport, spacing, neighbours, positions.size(),
                                              &validityRays))
    tasks.push_back(task);
  BakedProbes baked = bakeTasks(scene, tracer, basis, settings, std::move(tasks));
  const std::size_t n = positions.size();  // the neighbours' results are not returned
  baked.tasks.resize(n);
  baked.samples.resize(n);
  baked.coefficients.resize(n * std::size_t(baked.coefficientsPerProbe));
  baked.visibility.resize(n * std::size_t(baked.visibilityPerProbe));
  baked.placements = std::move(placements);
  baked.rays.validity += validityRays;
  return baked;
}

}  // namespace baker
