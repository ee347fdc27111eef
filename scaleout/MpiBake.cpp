#include "scaleout/MpiBake.h"

#include <fmt/format.h>

#include <chrono>
#include <thread>

#include "common/Error.h"
#include "common/PeakMemory.h"
#include "common/Timing.h"
#include "volume/AdaptiveAssembly.h"
#include "volume/LevelPacking.h"
#include "volume/MemoryEstimate.h"
#include "volume/VolumeAssembly.h"

namespace baker {
namespace {

// What each rank tells rank 0 about itself, in this order.
std::vector<double> rankSummary(const MpiBakeReport& report, int threads) {
  const BakeStats& s = report.stats;
  return {double(threads),       double(s.probes),          double(s.validProbes), double(s.relocatedProbes),
          double(s.invalidProbes), double(s.rays.total()), report.bakeSeconds,  double(peakMemoryBytes())};
}
constexpr std::size_t kSummaryValues = 8;

void readSummaries(const std::vector<double>& all, MpiBakeReport& report) {
  for (std::size_t r = 0; r * kSummaryValues < all.size(); ++r) {
    const double* v = all.data() + r * kSummaryValues;
    report.ranks.push_back({int(r), int(v[0]), std::int64_t(v[1]), std::int64_t(v[5]), v[6], v[7]});
    report.probes += std::int64_t(v[1]);
    report.validProbes += std::int64_t(v[2]);
    report.relocatedProbes += std::int64_t(v[3]);
    report.invalidProbes += std::int64_t(v[4]);
    report.raysTraced += std::int64_t(v[5]);
  }
}

// bakeWithMpi for an adaptive bake: each rank traces its share of the levels' bricks, rank 0 puts
// the parts together as `baker merge` does (AdaptiveAssembly) and writes the levels.
MpiBakeReport bakeLevelsWithMpi(const MpiSession& session, const BakeJob& job, const VolumeOutput& output,
                                const std::function<void(std::int64_t, std::int64_t)>& progress) {
  const AdaptivePlacement& placement = *job.placement();
  // Rank 0 holds every part, then the whole volume (volumeMemoryBytes counts the values twice):
  // refused before any rank traces.
  // As AdaptiveAssembly estimates it (whole bricks), so that it cannot refuse after the ranks traced.
  double placedProbes = 0.0;
  for (const std::vector<std::int64_t>& bricks : placement.bricks)
    placedProbes += double(bricks.size()) * kBrickSize * kBrickSize * kBrickSize;
  const double rootBytes = volumeMemoryBytes(placedProbes, job.basis());
  if (session.rank() == 0 && rootBytes > double(physicalMemoryBytes()))
    throw SettingError("spacing", fmt::format(": rank 0 would hold the parts of {} probes, then the whole volume, "
                                              "about {:.3g} GiB, more than this machine has; nothing was traced",
                                              std::int64_t(placedProbes), rootBytes / double(1ull << 30)));
  MpiBakeReport report;
  const auto start = std::chrono::steady_clock::now();
  AdaptiveVolume part = job.bakeLevels(&report.stats, progress);
  report.bakeSeconds = secondsSince(start);
  const std::vector<double> summaries = session.gatherToRoot(rankSummary(report, job.request().threads));
  if (session.rank() != 0) {
    const std::vector<float> packed = packLevels(part);
    part = AdaptiveVolume();  // sent as packed: one copy of the share while sending
    session.sendToRoot(packed);
    return report;
  }
  readSummaries(summaries, report);
  const auto gatherStart = std::chrono::steady_clock::now();
  const AdaptiveVolume header = levelsWithoutValues(part);
  AdaptiveAssembly assembly(part, "rank 0");
  assembly.add(std::move(part), "rank 0");
  const auto shares = everyShardsLevelBricks(placement.grids, placement.bricks, session.size());
  for (int r = 1; r < session.size(); ++r) {
    const Shard theirs{r, session.size()};
    std::vector<ProbeRows> share;
    for (int k = 0; k < placement.levels(); ++k) share.push_back(placement.rows(k, shares[std::size_t(r)][std::size_t(k)]));
    std::vector<float> values(packedLevelsSize(header, share));
    session.receiveFrom(r, values);
    assembly.add(unpackLevels(header, theirs, share, values), fmt::format("rank {}", r));
  }
  const AdaptiveVolume whole = assembly.finish();
  report.gatherSeconds = secondsSince(gatherStart);
  const auto writeStart = std::chrono::steady_clock::now();
  report.engineExport = writeLevels(whole, job.basis(), output);
  report.writeSeconds = secondsSince(writeStart);
  return report;
}

}  // namespace

int threadsPerRank(const MpiSession& session, int requestedThreads) {
  if (requestedThreads > 0) return requestedThreads;
  const int cores = int(std::max(1u, std::thread::hardware_concurrency()));
  return std::max(1, cores / std::max(1, session.ranksOnThisMachine()));
}

MpiBakeReport bakeWithMpi(const MpiSession& session, const BakeJob& job, const VolumeOutput& output,
                          const std::function<void(std::int64_t, std::int64_t)>& progress) {
  const std::optional<Shard>& shard = job.request().shard;
  if (!shard || shard->index != session.rank() || shard->count != session.size())
    throw std::logic_error("bakeWithMpi: the job's shard must be rank/size");
  if (job.placement()) return bakeLevelsWithMpi(session, job, output, progress);
  // Rank 0 will hold the whole volume: refused before it traces (its failure stops every rank),
  // not after hours of baking.
  if (session.rank() == 0)
    requireVolumeFitsInMemory(job.grid(), 1, job.basis(), physicalMemoryBytes(), job.settings().distanceValuesPerProbe());
  MpiBakeReport report;
  const auto start = std::chrono::steady_clock::now();
  Volume part = job.bake(&report.stats, progress);
  report.bakeSeconds = secondsSince(start);
  const std::vector<double> summaries =
      session.gatherToRoot(rankSummary(report, job.request().threads));
  if (session.rank() != 0) {
    const std::vector<float> packed = packBricks(part, shardBricks(part.grid, *shard));
    part = Volume();  // sent as packed: one copy of the share while sending
    session.sendToRoot(packed);
    return report;
  }
  readSummaries(summaries, report);
  const auto gatherStart = std::chrono::steady_clock::now();
  VolumeAssembly assembly(part, "rank 0");
  assembly.addBaked(part);
  const Volume like = volumeWithoutValues(part);
  part = Volume();  // in the assembly now: hold the whole volume, not this share as well
  for (int r = 1; r < session.size(); ++r) {
    const Shard theirs{r, session.size()};
    std::vector<float> values(packedSize(like, shardBricks(like.grid, theirs)));
    session.receiveFrom(r, values);
    assembly.addPacked(theirs, values);
  }
  const Volume whole = assembly.finish();
  report.gatherSeconds = secondsSince(gatherStart);
  const auto writeStart = std::chrono::steady_clock::now();
  report.engineExport = writeVolume(whole, job.basis(), output);
  report.writeSeconds = secondsSince(writeStart);
  return report;
}

}  // namespace baker
