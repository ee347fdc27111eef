#include "formats/PartMerge.h"

#include <fmt/format.h>

#include <chrono>
#include <optional>

#include "common/Error.h"
#include "common/Timing.h"
#include "formats/VolumeReader.h"
#include "volume/AdaptiveAssembly.h"
#include "volume/VolumeAssembly.h"

namespace baker {

namespace {

// The parts of an adaptive bake: every part read whole (a part holds only its share's bricks).
MergeReport mergeAdaptiveParts(const std::vector<std::string>& parts, const VolumeOutput& output) {
  MergeReport report;
  const auto start = std::chrono::steady_clock::now();
  std::optional<AdaptiveAssembly> assembly;
  for (const std::string& path : parts) {
    AdaptiveVolume part = readLevels(path);
    if (!assembly) assembly.emplace(part, path);
    assembly->add(std::move(part), path);
  }
  const AdaptiveVolume volume = assembly->finish();
  report.readSeconds = secondsSince(start);
  const std::unique_ptr<Basis> basis = basisOf(volume.coarsest());
  requireLevelsWritable(output, int(volume.levels.size()));
  const auto writeStart = std::chrono::steady_clock::now();
  report.engineExport = writeLevels(volume, *basis, output);
  report.writeSeconds = secondsSince(writeStart);
  report.shards = int(parts.size());
  for (const Volume& level : volume.levels) {
    report.probes += level.rows.count(level.grid);
    for (const ProbeState s : level.states) report.invalidProbes += s == ProbeState::Invalid;
  }
  report.levels = int(volume.levels.size());
  report.basis = basis->name();
  return report;
}

}  // namespace

MergeReport mergeParts(const std::vector<std::string>& parts, const VolumeOutput& output) {
  if (parts.empty()) throw InputError("merge: no parts given");
  // One kind of part: a uniform part among an adaptive bake's would be read whole before it is refused.
  const bool adaptive = levelCountOf(parts.front()) > 1;
  for (const std::string& path : parts)
    if ((levelCountOf(path) > 1) != adaptive)
      throw InputError(fmt::format("{}: {} volume, but {} is {}: the parts are not of one bake", path,
                                   adaptive ? "a uniform" : "an adaptive", parts.front(),
                                   adaptive ? "a part of an adaptive bake" : "a part of a uniform bake"));
  if (adaptive) return mergeAdaptiveParts(parts, output);
  MergeReport report;
  const auto start = std::chrono::steady_clock::now();
  std::optional<VolumeAssembly> assembly;
  for (const std::string& path : parts) {
    const Volume part = readVolume(path, PartReading::OwnBricks);
    if (!assembly) assembly.emplace(part, path);
    assembly->add(part, path);
  }
  Volume volume = assembly->finish();
  report.readSeconds = secondsSince(start);
  const std::unique_ptr<Basis> basis = basisOf(volume);
  requireWritable(output, *basis);
  const auto writeStart = std::chrono::steady_clock::now();
  report.engineExport = writeVolume(volume, *basis, output);
  report.writeSeconds = secondsSince(writeStart);
  report.shards = int(parts.size());
  report.probes = volume.grid.probeCount();
  for (const ProbeState s : volume.states) report.invalidProbes += s == ProbeState::Invalid;
  report.basis = basis->name();
  return report;
}

}  // namespace baker
