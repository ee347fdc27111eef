#include "cli/MpiBakeCommand.h"

#include <fmt/format.h>

#include <chrono>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli/CommandLine.h"
#include "cli/ProgressBar.h"
#include "common/PeakMemory.h"
#include "common/Timing.h"
#include "scaleout/MpiBake.h"

namespace baker {
namespace {

nlohmann::json mpiJson(const BakeJob& job, const MpiBakeReport& r, const VolumeOutput& output, int ranks,
                       double totalSeconds) {
  nlohmann::json perRank = nlohmann::json::array();
  for (const RankReport& rank : r.ranks)
    perRank.push_back({{"rank", rank.rank}, {"threads", rank.threads}, {"probes", rank.probes},
                       {"rays_traced", rank.raysTraced}, {"bake_seconds", rank.bakeSeconds},
                       {"peak_memory_bytes", rank.peakMemoryBytes}});
  const ProbeGrid& grid = job.grid();
  return {{"output", output.path},
          {"format", volumeFormatName(output.format)},
          {"basis", job.basis().name()},
          {"ranks", ranks},
          {"grid", {{"dims", {grid.dims.x(), grid.dims.y(), grid.dims.z()}},
                    {"origin", {grid.origin.x(), grid.origin.y(), grid.origin.z()}},
                    {"spacing", grid.spacing}}},
          {"probes", r.probes},
          {"probe_states", {{"valid", r.validProbes}, {"relocated", r.relocatedProbes}, {"invalid", r.invalidProbes}}},
          {"rays_traced", r.raysTraced},
          {"seconds", {{"bake_rank_0", r.bakeSeconds}, {"gather", r.gatherSeconds}, {"write", r.writeSeconds},
                       {"total", totalSeconds}}},
          {"per_rank", perRank},
          // Rank 0's, after gathering and writing the whole volume (per_rank has each rank's bake).
          {"peak_memory_bytes", peakMemoryBytes()}};
}

void printMpiSummary(const MpiBakeReport& r, const VolumeOutput& output, const BakeJob& job, int ranks) {
  std::cerr << fmt::format("baked {} probes on {} ranks ({} relocated, {} invalid and filled), {} rays; gather {:.2f} s, "
                           "write {:.2f} s\n",
                           r.probes, ranks, r.relocatedProbes, r.invalidProbes, r.raysTraced, r.gatherSeconds,
                           r.writeSeconds);
  for (const RankReport& rank : r.ranks)
    std::cerr << fmt::format("  rank {}: {} probes, {} threads, {:.2f} s, peak memory {:.0f} MiB\n", rank.rank,
                             rank.probes, rank.threads, rank.bakeSeconds, rank.peakMemoryBytes / 1048576.0);
  std::cout << fmt::format("wrote {} ({}, {} coefficients per probe)\n", output.path, job.basis().name(),
                           job.basis().totalCoefficients());
  if (!r.engineExport.engine.empty())
    std::cout << fmt::format("  for {}: {}\n", r.engineExport.engine, r.engineExport.conversion);
}

}  // namespace

int bakeOverMpi(const CLI::App& app, BakeOptions options, const VolumeOutput& output, const MpiPrinting& printing) {
  const auto start = std::chrono::steady_clock::now();
  MpiSession session;
  try {
    const bool root = session.rank() == 0;
    options.request.shard = Shard{session.rank(), session.size()};
    options.request.threads = threadsPerRank(session, options.request.threads);
    std::ostringstream silenced;
    std::ostream& log = root && !printing.quiet ? std::cerr : silenced;
    const std::unique_ptr<BakeJob> job = prepareBake(app, options, log);
    printExportPlan(log, output, job->basis(), job->settings().projection.signal, printing.nonNegativeForFormat);
    log << fmt::format("mpi: {} ranks, each baking a shard of the bricks with {} threads ({} ranks on this machine)\n",
                       session.size(), options.request.threads, session.ranksOnThisMachine());
    MpiBakeReport report;
    {
      ProgressBar bar("baking rank 0's shard", root && !printing.quiet);
      report = bakeWithMpi(session, *job, output, [&](std::int64_t done, std::int64_t total) { bar.update(done, total); });
    }
    if (!root) return 0;
    for (const std::string& warning : report.engineExport.warnings)
      std::cerr << fmt::format("baker: warning: {}: {}\n", report.engineExport.engine, warning);
    if (printing.json)
      std::cout << mpiJson(*job, report, output, session.size(), secondsSince(start)).dump(2) << "\n";
    else
      printMpiSummary(report, output, *job, session.size());
    return 0;
  } catch (...) {
    session.abort(reportFailure(fmt::format("baker (rank {} of {})", session.rank(), session.size()),
                                std::current_exception()));
  }
}

}  // namespace baker
