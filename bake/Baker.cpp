#include "bake/Baker.h"

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <atomic>
#include <chrono>
#include <vector>

#include "bake/ProbeValidity.h"
#include "common/Error.h"
#include "volume/InvalidProbeFill.h"
#include "volume/MemoryEstimate.h"

namespace baker {
namespace {

// Neighbouring probes trace differently rotated direction sets: the rotation follows the
// parity of the probe's index on each axis, so all 26 neighbours of a probe differ from it.
constexpr int kRotations = 8;
int rotationOf(int i, int j, int k) { return (i & 1) + 2 * (j & 1) + 4 * (k & 1); }

// A brick's values as the probe baker writes them, task after task; kept from brick to brick.
struct BrickScratch {
  std::vector<float> coefficients, skyDirect, skyBounced, visibility, distances;
};

// The probes of brick `brick`: placed (moved out of geometry, or marked invalid) and traced,
// their coefficients, directly seen sky, sky visibility and distance moments written into `volume`.
void bakeBrick(const RayTracer& tracer, const BakeSettings& settings, const ProbeBaker& probeBaker,
               const std::vector<Eigen::Vector3f>& testDirections, std::int64_t brick, std::uint64_t firstId,
               Volume& volume, RayCounts& counts, RoundTally& tally, BrickScratch& scratch) {
  const ProbeGrid& grid = volume.grid;
  std::vector<ProbeTask> candidates;
  std::vector<std::int64_t> rows;  // each candidate's row in the volume's arrays
  forEachHeldProbeOfBrick(grid, volume.rows, brick, [&](int i, int j, int k, std::int64_t row) {
    if (volume.states[row] == ProbeState::Interpolated) return;
    volume.states[row] = ProbeState::Valid;
    rows.push_back(row);
    candidates.push_back({grid.position(i, j, k).cast<float>(), firstId + std::uint64_t(grid.linearIndex(i, j, k)),
                          rotationOf(i, j, k)});
  });
  if (settings.transport.probeValidity) {
    const ValidityOptions validityOptions;
    // Placed side by side like the probes' tracing (ProbeBaker::bake). Isolated so that a
    // waiting thread does not start a brick of its own inside this one.
    std::vector<std::int64_t> validityRays(candidates.size(), 0);
    tbb::this_task_arena::isolate([&] {
      tbb::parallel_for(std::size_t(0), candidates.size(), [&](std::size_t c) {
        const ProbePlacement placement = placeProbe(tracer, candidates[c].position, float(grid.spacing),
                                                    testDirections, validityOptions, &validityRays[c]);
        volume.states[rows[c]] = placement.state;
        volume.offsets[rows[c]] = placement.offset;
        candidates[c].position += placement.offset;
      });
    });
    for (std::int64_t n : validityRays) counts.validity += n;
  }
  std::vector<ProbeTask> tasks;
  std::vector<std::int64_t> taskRows;
  for (std::size_t c = 0; c < candidates.size(); ++c)
    if (volume.states[rows[c]] != ProbeState::Invalid) {
      tasks.push_back(candidates[c]);
      taskRows.push_back(rows[c]);
    }
  auto arrays = volume.floatRows();
  // In Volume::floatRows()'s order, which every copy below follows.
  std::vector<float>* buffers[] = {&scratch.coefficients, &scratch.skyDirect, &scratch.skyBounced, &scratch.visibility,
                                   &scratch.distances};
  for (std::size_t a = 0; a < arrays.size(); ++a) buffers[a]->resize(tasks.size() * std::size_t(arrays[a].width));
  probeBaker.bake(tasks, scratch.coefficients.data(), scratch.visibility.data(), &counts, nullptr, &tally,
                  {volume.distanceMap, volume.distanceMomentsPerProbe() > 0 ? scratch.distances.data() : nullptr},
                  volume.keepsSkyDirect ? scratch.skyDirect.data() : nullptr,
                  volume.keepsSkyBounced ? scratch.skyBounced.data() : nullptr);
  for (std::size_t a = 0; a < arrays.size(); ++a) {
    const std::size_t width = std::size_t(arrays[a].width);
    for (std::size_t t = 0; t < tasks.size(); ++t)
      std::copy_n(buffers[a]->data() + t * width, width, arrays[a].values->data() + taskRows[t] * width);
  }
}

}  // namespace

void requireFiniteBake(const Volume& volume) {
  for (std::size_t i = 0; i < volume.coefficients.size(); ++i)
    if (!std::isfinite(volume.coefficients[i]))
      throw NumericalError(fmt::format("probe {} of the bake has a non-finite coefficient (the scene's radiance "
                                       "overflows float); nothing was written",
                                       volume.rows.probeAt(volume.grid, std::int64_t(i) / volume.coefficientsPerProbe)));
  for (const std::vector<float>* sky : {&volume.skyDirect, &volume.skyBounced})
    for (std::size_t i = 0; i < sky->size(); ++i)
      if (!std::isfinite((*sky)[i]))
        throw NumericalError(fmt::format("probe {} of the bake has a non-finite coefficient of its sky light kept "
                                         "apart (the sky's radiance overflows float); nothing was written",
                                         volume.rows.probeAt(volume.grid, std::int64_t(i) / volume.coefficientsPerProbe)));
  for (std::size_t i = 0; i < volume.visibility.size(); ++i)
    if (!std::isfinite(volume.visibility[i]))
      throw NumericalError(fmt::format("probe {} of the bake has a non-finite sky visibility; nothing was written",
                                       volume.rows.probeAt(volume.grid, std::int64_t(i) / volume.visibilityPerProbe)));
}

namespace {

// Every brick in linear order, or the shard's.
std::vector<std::int64_t> bricksToBake(const ProbeGrid& grid, const std::optional<Shard>& shard) {
  if (shard) return shardBricks(grid, *shard);
  const Eigen::Vector3i b = grid.brickCounts();
  std::vector<std::int64_t> all(std::size_t(b.x()) * b.y() * b.z());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = std::int64_t(i);
  return all;
}

}  // namespace

BrickBaker::BrickBaker(const Scene& scene, const RayTracer& tracer, const Basis& basis, const BakeSettings& settings)
    : tracer_(tracer), basis_(basis), settings_(settings), testDirections_(validityDirections(ValidityOptions{})) {
  if (settings.rays <= 0) throw SettingError("rays", fmt::format("must be positive, got {}", settings.rays));
  const auto start = std::chrono::steady_clock::now();
  probeBaker_ = std::make_unique<ProbeBaker>(scene, tracer, basis, settings, kRotations);
  operatorSeconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

BrickBaker::~BrickBaker() = default;

Volume BrickBaker::emptyVolume(const ProbeGrid& grid, const ProbeRows& rows) const {
  Volume volume;
  volume.grid = grid;
  volume.rows = rows;
  volume.basisName = basis_.name();
  volume.coefficientsPerProbe = probeBaker_->coefficientsPerProbe();
  volume.visibilityPerProbe = probeBaker_->visibilityPerProbe();
  volume.keepsSkyDirect = probeBaker_->keepsSkyDirect();
  volume.keepsSkyBounced = probeBaker_->keepsSkyBounced();
  const std::size_t probes = std::size_t(volume.rows.count(grid));
  volume.coefficients.assign(probes * volume.coefficientsPerProbe, 0.0f);
  volume.skyDirect.assign(probes * std::size_t(volume.skyDirectPerProbe()), 0.0f);
  volume.skyBounced.assign(probes * std::size_t(volume.skyBouncedPerProbe()), 0.0f);
  volume.visibility.assign(probes * volume.visibilityPerProbe, 0.0f);
  volume.states.assign(probes, ProbeState::Invalid);
  volume.offsets.assign(probes, Eigen::Vector3f::Zero());
  // Probes inside geometry keep zeros: every point lies beyond them, so leak-aware reading drops them.
  if (settings_.distanceMapSize > 0) {
    volume.distanceMap = DistanceMapLayout::baked(settings_.distanceMapSize, DistanceMapLayout::kCapSpacings * grid.spacing);
    volume.distanceMoments.assign(probes * std::size_t(volume.distanceMomentsPerProbe()), 0.0f);
  }
  return volume;
}

void BrickBaker::bake(Volume& volume, const std::vector<std::int64_t>& bricks, std::uint64_t firstId, BakeStats* stats,
                      const std::function<void()>& brickDone) const {
  const auto start = std::chrono::steady_clock::now();
  const int brickCount = int(bricks.size());
  std::vector<RayCounts> brickRays(brickCount);
  std::vector<RoundTally> brickTallies(brickCount);
  tbb::parallel_for(tbb::blocked_range<int>(0, brickCount, 1), [&](const tbb::blocked_range<int>& range) {
    BrickScratch scratch;
    for (int n = range.begin(); n < range.end(); ++n) {
      bakeBrick(tracer_, settings_, *probeBaker_, testDirections_, bricks[n], firstId, volume, brickRays[n],
                brickTallies[n], scratch);
      if (brickDone) brickDone();
    }
  });
  if (!stats) return;
  for (const std::int64_t b : bricks) stats->probes += volume.rows.probesHeld(volume.grid, b);
  stats->bricks += brickCount;
  for (const RayCounts& c : brickRays) stats->rays += c;  // in brick order: the same sums every run
  for (const RoundTally& t : brickTallies) stats->lattice += t;
  stats->traceSeconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void BrickBaker::finishStats(const std::vector<const Volume*>& volumes, BakeStats* stats) const {
  if (!stats) return;
  stats->raysPerProbe = settings_.rays;
  for (const Volume* volume : volumes)
    for (ProbeState s : volume->states) {
      stats->validProbes += s == ProbeState::Valid;
      stats->relocatedProbes += s == ProbeState::Relocated;
      stats->interpolatedProbes += s == ProbeState::Interpolated;
    }
  stats->invalidProbes = stats->probes - stats->validProbes - stats->relocatedProbes - stats->interpolatedProbes;
  stats->conditionNumber = probeBaker_->conditionNumber();
  stats->shOrder = probeBaker_->shOrder();
  stats->projectionSeconds = probeBaker_->projectionSeconds();
  stats->operatorSeconds = operatorSeconds_;
}

Volume bakeVolume(const Scene& scene, const RayTracer& tracer, const Basis& basis, const ProbeGrid& grid,
                  const BakeSettings& settings, BakeStats* stats,
                  const std::function<void(std::int64_t, std::int64_t)>& progress,
                  const std::optional<Shard>& shard) {
  if (settings.rays <= 0) throw SettingError("rays", fmt::format("must be positive, got {}", settings.rays));
  requireVolumeFitsInMemory(grid, shard ? shard->count : 1, basis, physicalMemoryBytes(), settings.distanceValuesPerProbe());
  const std::vector<std::int64_t> toBake = bricksToBake(grid, shard);
  const BrickBaker baker(scene, tracer, basis, settings);
  const auto start = std::chrono::steady_clock::now();
  Volume volume = baker.emptyVolume(grid, shard ? ProbeRows(grid, toBake) : ProbeRows());
  if (stats) *stats = BakeStats{};
  std::atomic<std::int64_t> bricksDone{0};
  const std::int64_t brickCount = std::int64_t(toBake.size());
  baker.bake(volume, toBake, 0, stats, [&] {
    const std::int64_t done = ++bricksDone;
    if (progress) progress(done, brickCount);
  });
  volume.shard = shard;
  if (!shard) {
    fillInvalidProbes(grid, volume.states, volume.coefficientsPerProbe, volume.coefficients);
    fillInvalidProbes(grid, volume.states, volume.visibilityPerProbe, volume.visibility);
    fillInvalidProbes(grid, volume.states, volume.skyDirectPerProbe(), volume.skyDirect);
    fillInvalidProbes(grid, volume.states, volume.skyBouncedPerProbe(), volume.skyBounced);
  }
  requireFiniteBake(volume);
  baker.finishStats({&volume}, stats);
  // Tracing, projecting and filling: everything after the operators.
  if (stats) stats->traceSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return volume;
}

}  // namespace baker
