#pragma once
#include <tbb/global_control.h>

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "bake/AdaptivePlacement.h"
#include "bake/BakeRequest.h"
#include "bake/Baker.h"
#include "bake/ProbeBaker.h"
#include "bake/ProbesAt.h"
#include "basis/Basis.h"
#include "scene/RayTracer.h"
#include "scene/Scene.h"
#include "scene/SceneEffects.h"
#include "volume/AdaptiveVolume.h"
#include "volume/ProbeGrid.h"
#include "volume/Volume.h"

namespace baker {

// One bake, from a request to a volume: the library's entry point. Constructing it validates
// the request (validateBakeRequest), loads the scene, lays out the grid, plans the effects the
// scene calls for and builds the BVH; bake() then traces the whole grid and probesAt() single
// probes, both with the same settings. What a front end prints comes from the accessors.
class BakeJob {
 public:
  // `observer`, when given, hears every ray the job's tracer traces (a benchmark's hook).
  explicit BakeJob(BakeRequest request, RayObserver* observer = nullptr);
  ~BakeJob();
  BakeJob(const BakeJob&) = delete;
  BakeJob& operator=(const BakeJob&) = delete;

  const BakeRequest& request() const { return request_; }
  const Basis& basis() const { return *basis_; }
  const Scene& scene() const { return *scene_; }
  const RayTracer& tracer() const { return *tracer_; }
  // The grid: a uniform bake's, or an adaptive bake's coarsest level.
  const ProbeGrid& grid() const { return grid_; }
  // Where an adaptive bake's probes go, decided when the job is made; null for a uniform bake.
  const AdaptivePlacement* placement() const { return placement_.get(); }
  // How the grid's spacing was chosen: "as given", or the default and why it is what it is.
  const std::string& spacingReason() const { return spacingReason_; }
  const std::vector<PlannedEffect>& plan() const { return plan_; }
  const BakeSettings& settings() const { return settings_; }
  double loadSeconds() const { return loadSeconds_; }
  double bvhSeconds() const { return bvhSeconds_; }
  // The most rays one probe may trace: settings().rays when fixed, the preset's limit otherwise.
  std::int64_t rayLimit() const;

  // Every probe of the grid; the volume's `settings` record what made it (FORMAT.md).
  // `progress` hears (bricks done, bricks in all) from worker threads.
  // A uniform bake only (std::logic_error otherwise).
  // Bricks of 8³ probes the whole bake traces (every level's placed ones, adaptive), and those of
  // its shard (all of them when it is not cut into shards).
  std::int64_t bricksInBake() const;
  std::int64_t bricksInShard() const;
  Volume bake(BakeStats* stats = nullptr, const std::function<void(std::int64_t, std::int64_t)>& progress = {}) const;
  // Every level of an adaptive bake, or the one level of a uniform one.
  AdaptiveVolume bakeLevels(BakeStats* stats = nullptr,
                            const std::function<void(std::int64_t, std::int64_t)>& progress = {}) const;
  // Probes at these positions, placed and traced as the grid's would be (ids 0, 1, ...).
  BakedProbes probesAt(const std::vector<Eigen::Vector3f>& positions) const;

 private:
  BakeRequest request_;
  std::unique_ptr<tbb::global_control> threadLimit_;
  std::unique_ptr<Basis> basis_;
  std::unique_ptr<Scene> scene_;
  std::unique_ptr<RayTracer> tracer_;
  ProbeGrid grid_;
  std::unique_ptr<AdaptivePlacement> placement_;
  std::string spacingReason_;
  std::vector<PlannedEffect> plan_;
  BakeSettings settings_;
  double loadSeconds_ = 0.0, bvhSeconds_ = 0.0;
};

}  // namespace baker
