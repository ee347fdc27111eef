#pragma once
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>
#include <optional>

#include "bake/ProbeBaker.h"
#include "bake/Transport.h"
#include "basis/Basis.h"
#include "scene/RayTracer.h"
#include "scene/Scene.h"
#include "volume/ProbeGrid.h"
#include "volume/Volume.h"

namespace baker {

struct BakeStats {
  std::int64_t probes = 0;
  std::int64_t bricks = 0;
  int raysPerProbe = 0;  // settings.rays: a fixed count, or the size of round 0's lattices
  RoundTally lattice;    // lattice directions of the probes traced (the valid ones)
  RayCounts rays;
  std::int64_t validProbes = 0, relocatedProbes = 0, invalidProbes = 0, interpolatedProbes = 0;
  double conditionNumber = 0.0;  // worst of the basis's Gram matrices
  int shOrder = 0;               // SH order the samples are fitted with on their way to the basis
  double operatorSeconds = 0.0;  // building the projection operators
  double traceSeconds = 0.0;     // tracing and projecting every brick (wall)
  double projectionSeconds = 0.0;  // of which projecting, summed over threads
};

// Bakes bricks of a grid into a volume: what every bake shares (the uniform one, each level of an
// adaptive one), so that the projection operators are built once per bake.
class BrickBaker {
 public:
  BrickBaker(const Scene& scene, const RayTracer& tracer, const Basis& basis, const BakeSettings& settings);
  ~BrickBaker();

  // A volume on `grid` holding `rows`: zeros, every probe Invalid until its brick is baked.
  Volume emptyVolume(const ProbeGrid& grid, const ProbeRows& rows) const;
  // Places and traces the probes of `bricks` (linear brick indices of volume.grid, held by
  // volume.rows), except those already Interpolated, which keep their values. Probe p traces
  // the random stream of id firstId + p, so that levels of an adaptive bake draw their own.
  // Adds what it traced to *stats (probes, bricks, rays, lattice, seconds); `brickDone` hears each brick.
  void bake(Volume& volume, const std::vector<std::int64_t>& bricks, std::uint64_t firstId, BakeStats* stats,
            const std::function<void()>& brickDone) const;
  // What only the end of a bake knows: probe states, operators, timings.
  void finishStats(const std::vector<const Volume*>& volumes, BakeStats* stats) const;

 private:
  const RayTracer& tracer_;
  const Basis& basis_;
  BakeSettings settings_;
  std::unique_ptr<ProbeBaker> probeBaker_;
  std::vector<Eigen::Vector3f> testDirections_;
  double operatorSeconds_ = 0.0;
};

// NumericalError naming the probe when a value of the bake is not finite: none reaches a file.
void requireFiniteBake(const Volume& volume);

// Bakes every probe of `grid`: each traces settings.rays directions (one path each, see
// PathIntegrator), or with adaptive settings.convergence as many as it needs, and stores the
// irradiance they imply, E(n) = ∫ L max(0, n·ω) dω (full irradiance, not E/π), in `basis`, plus
// its sky visibility. Probes inside geometry are moved
// out or, failing that, filled from valid neighbours (ProbeValidity). The result depends on
// settings.transport.seed and not on the number of threads.
// `progress`, when given, hears (bricks done, bricks in all) from worker threads.
// With `shard`, only the shard's bricks are baked and nothing is filled (Volume::shard): every
// probe's values are the same bits as in the whole bake, and merging the parts fills them.
Volume bakeVolume(const Scene& scene, const RayTracer& tracer, const Basis& basis, const ProbeGrid& grid,
                  const BakeSettings& settings, BakeStats* stats,
                  const std::function<void(std::int64_t, std::int64_t)>& progress = {},
                  const std::optional<Shard>& shard = std::nullopt);

}  // namespace baker
