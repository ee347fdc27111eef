#include "bake/BakeJob.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <set>

#include "bake/AdaptiveBaker.h"
#include "bake/ProbeConvergence.h"
#include "bake/SkyProjection.h"
#include "bake/TransportPlan.h"
#include "basis/BasisRegistry.h"
#include "basis/DiffuseResponse.h"
#include "basis/StoredSignal.h"
#include "common/FileHash.h"
#include "common/Timing.h"
#include "scene/GltfLoader.h"
#include "scene/SceneCensus.h"
#include "volume/MemoryEstimate.h"

namespace baker {
namespace {

BakeSettings bakeSettings(const BakeRequest& request, std::vector<PlannedEffect>& plan) {
  BakeSettings settings;
  settings.rays = request.rays;
  if (const QualityPreset* preset = request.quality.empty() ? nullptr : findQualityPreset(request.quality)) {
    settings.rays = preset->rays;
    settings.convergence = preset->convergence;
  }
  settings.projection.window = request.window;
  settings.projection.nonNegative = request.nonNegative;
  settings.projection.signal = parseStoredSignal(request.signal);
  settings.transport = transportSettings(plan, request.bounces, request.seed);
  settings.distanceMapSize = request.distanceMapSize();
  settings.sharedReflectionCell = float(request.sharedReflectionCell);
  return settings;
}

// What made the volume, as its file records it (docs/FORMAT.md, "settings").
void recordSettings(const BakeJob& job, Volume& volume) {
  const BakeRequest& request = job.request();
  const BakeSettings& settings = job.settings();
  const ConvergenceSettings& convergence = settings.convergence;
  volume.settings["rays"] = std::to_string(settings.rays);
  volume.settings["quality"] = qualityName(request);
  if (convergence.adaptive()) {
    volume.settings["target_error"] = fmt::format("{}", convergence.targetError);
    volume.settings["min_rays"] = std::to_string(raysAfterRounds(settings.rays, convergence.minRounds));
    volume.settings["max_rays"] = std::to_string(raysAfterRounds(settings.rays, convergence.maxRounds));
  }
  volume.settings["bounces"] = std::to_string(settings.transport.bounces);
  volume.settings["seed"] = std::to_string(request.seed);
  volume.settings["sampler"] = ProbeBaker::samplerName(settings);
  if (settings.sharedReflectionCell > 0.0f)
    volume.settings["share_reflections"] = fmt::format("{}", request.sharedReflectionCell);
  for (const PlannedEffect& e : job.plan()) volume.settings["effect." + e.name] = e.simulated ? "on" : "off";
  volume.settings["window"] = std::to_string(request.window.hannWidth);
  volume.settings["non_negative"] = request.nonNegative ? "true" : "false";
  volume.settings["signal"] = storedSignalName(job.settings().projection.signal);
  for (const auto& [key, value] : parameterSettings(job.basis().parameters())) volume.settings[key] = value;
  if (job.placement()) {
    volume.settings["placement"] = "adaptive";
    volume.settings["levels"] = std::to_string(job.placement()->levels());
    volume.settings["margin_cells"] = std::to_string(job.placement()->marginCells);
  }
  volume.settings["scene"] = std::filesystem::path(request.scenePath).filename().string();
  volume.settings["scene_fnv1a64"] = fileHash(request.scenePath);
  // The sky as the bake saw it: none when its effect was turned off.
  const Environment seen = settings.transport.environment ? job.scene().environment : Environment();
  volume.settings["sky"] = skyDescription(seen);
  volume.sky = recordSky(seen);
}

// The grid at the default spacing (volume/ProbeGrid.h), widened until it fits this machine's
// memory and the probe limit; `reason` says how the spacing was chosen, for the plan.
ProbeGrid defaultGrid(const Eigen::AlignedBox3f& bounds, const Basis& basis, int distanceValues, std::string& reason) {
  const double longest = bounds.isEmpty() ? 0.0 : double(bounds.sizes().maxCoeff());
  double spacing = defaultSpacing(bounds);
  reason = spacing < kDefaultMaxSpacing ? fmt::format("the default: the scene's longest side ({:.4g} m) / {}", longest,
                                                      kDefaultProbesAlongLongestSide)
                                        : fmt::format("the default: {} m at most, in a scene {:.4g} m long",
                                                      kDefaultMaxSpacing, longest);
  const double bytesPerProbe = volumeMemoryBytes(1.0, basis, distanceValues);
  const double memoryProbes = double(physicalMemoryBytes()) / bytesPerProbe;
  const double limit = std::min(double(kMaxBakeProbes), memoryProbes);
  const double firstSpacing = spacing;
  double probes = probesPerAxis(bounds, spacing).prod();
  // Each step widens by the cube root of the excess (a little more, for the rounding up of cells),
  // which lands within a few steps.
  for (int step = 0; probes > limit && step < 64; ++step) {
    spacing *= std::cbrt(probes / limit) * 1.01;
    probes = probesPerAxis(bounds, spacing).prod();
  }
  if (spacing != firstSpacing)
    reason = fmt::format("widened from the default {:.4g} m, whose {:.3g} probes would need {:.3g} GiB, more than this "
                         "machine's {:.3g} GiB (or the limit of {} probes); give a spacing to choose another (baked in shards, "
                         "each machine holds its share and the merge the whole volume: docs/SCALING.md)",
                         firstSpacing, probesPerAxis(bounds, firstSpacing).prod(),
                         probesPerAxis(bounds, firstSpacing).prod() * bytesPerProbe / double(1ull << 30),
                         double(physicalMemoryBytes()) / double(1ull << 30), kMaxBakeProbes);
  return makeProbeGrid(bounds, spacing, kMaxBakeProbes);
}

}  // namespace

BakeJob::BakeJob(BakeRequest request, RayObserver* observer) : request_(std::move(request)) {
  validateBakeRequest(request_);
  basis_ = makeBasis(request_.basis, request_.basisParameters());
  // A radiance volume is read through its functions' diffuse response: lobes too sharp for it are
  // refused before anything is traced, not when the volume is first read.
  if (parseStoredSignal(request_.signal) == StoredSignal::Radiance)
    for (int c = 0; c < 3; ++c) diffuseResponseOf(*basis_, c);
  if (request_.threads > 0)
    threadLimit_ = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, request_.threads);
  const auto start = std::chrono::steady_clock::now();
  scene_ = std::make_unique<Scene>(loadGltf(request_.scenePath, request_.scene));
  loadSeconds_ = secondsSince(start);
  ProbeGrid finestGrid;
  if (request_.adaptive()) {
    const double finest = request_.spacing ? *request_.spacing : defaultSpacing(scene_->bounds);
    spacingReason_ = request_.spacing ? "as given, at the finest level" : "the default, at the finest level";
    finestGrid = makeProbeGrid(scene_->bounds, finest, std::int64_t(kMaxLevelGridProbes));
    grid_ = levelGrids(finestGrid, request_.levels).front();
  } else if (request_.spacing) {
    grid_ = makeProbeGrid(scene_->bounds, *request_.spacing, kMaxBakeProbes);
    spacingReason_ = "as given";
  } else {
    grid_ = defaultGrid(scene_->bounds, *basis_, DistanceMapLayout::baked(request_.distanceMapSize(), 0.0).valuesPerProbe(),
                        spacingReason_);
  }
  plan_ = planEffects(*scene_, takeCensus(*scene_));
  turnOffEffects(plan_, request_.turnedOff);
  settings_ = bakeSettings(request_, plan_);
  const auto bvhStart = std::chrono::steady_clock::now();
  tracer_ = std::make_unique<RayTracer>(*scene_, settings_.transport.alphaFilters, observer);
  bvhSeconds_ = secondsSince(bvhStart);
  if (request_.adaptive())
    placement_ = std::make_unique<AdaptivePlacement>(
        placeAdaptive(*scene_, *tracer_, finestGrid, request_.levels, request_.marginCells, kMaxBakeProbes));
}

BakeJob::~BakeJob() = default;

std::int64_t BakeJob::rayLimit() const {
  return settings_.convergence.adaptive() ? raysAfterRounds(settings_.rays, settings_.convergence.maxRounds)
                                          : std::int64_t(settings_.rays);
}

std::int64_t BakeJob::bricksInBake() const {
  if (!placement_) return grid_.brickCount();
  std::int64_t bricks = 0;
  for (const std::vector<std::int64_t>& level : placement_->bricks) bricks += std::int64_t(level.size());
  return bricks;
}

std::int64_t BakeJob::bricksInShard() const {
  if (!request_.shard) return bricksInBake();
  if (!placement_) return std::int64_t(shardBricks(grid_, *request_.shard).size());
  std::int64_t bricks = 0;
  for (const auto& level : shardLevelBricks(placement_->grids, placement_->bricks, *request_.shard))
    bricks += std::int64_t(level.size());
  return bricks;
}

Volume BakeJob::bake(BakeStats* stats, const std::function<void(std::int64_t, std::int64_t)>& progress) const {
  if (placement_) throw std::logic_error("BakeJob::bake: an adaptive bake has levels (bakeLevels)");
  Volume volume = bakeVolume(*scene_, *tracer_, *basis_, grid_, settings_, stats, progress, request_.shard);
  recordSettings(*this, volume);
  return volume;
}

AdaptiveVolume BakeJob::bakeLevels(BakeStats* stats,
                                   const std::function<void(std::int64_t, std::int64_t)>& progress) const {
  if (!placement_) {
    AdaptiveVolume volume;
    volume.levels.push_back(bake(stats, progress));
    return volume;
  }
  AdaptiveVolume volume = bakeAdaptive(*scene_, *tracer_, *basis_, *placement_, settings_, stats, progress, request_.shard);
  recordSettings(*this, volume.levels.front());
  return volume;
}

BakedProbes BakeJob::probesAt(const std::vector<Eigen::Vector3f>& positions) const {
  if (!(settings_.sharedReflectionCell > 0.0f))
    return bakeProbesAt(*scene_, *tracer_, *basis_, settings_, grid_.spacing, positions);
  // Shared reflections: each probe shares with the grid's probes of a brick about it, as a
  // probe of the grid would in a volume bake.
  std::set<std::int64_t> around;
  for (const Eigen::Vector3f& position : positions) {
    const Eigen::Vector3d cell = (position.cast<double>() - grid_.origin) / grid_.spacing;
    Eigen::Vector3i lo, hi;
    for (int a = 0; a < 3; ++a) {
      const int nearest = int(std::clamp(std::lround(cell[a]), 0L, long(grid_.dims[a] - 1)));
      lo[a] = std::max(0, nearest - kBrickSize / 2);
      hi[a] = std::min(grid_.dims[a], lo[a] + kBrickSize);
    }
    for (int k = lo.z(); k < hi.z(); ++k)
      for (int j = lo.y(); j < hi.y(); ++j)
        for (int i = lo.x(); i < hi.x(); ++i) around.insert(grid_.linearIndex(i, j, k));
  }
  std::vector<Eigen::Vector3f> neighbours;
  for (const std::int64_t p : around) neighbours.push_back(grid_.position(p).cast<float>());
  return bakeProbesAt(*scene_, *tracer_, *basis_, settings_, grid_.spacing, positions, neighbours);
}

}  // namespace baker
