#include "formats/PartMerge.h"

#include <fmt/format.h>

#include <chrono>
#include <optional>

#include "common/Error.h"
#include "common/Timing.h"
#include "formats/VolumeReader.h"
#include "volume/VolumeAssembly.h"

namespace baker {

MergeReport mergeParts(const std::vector<std::string>& parts, const VolumeOutput& output) {
  if (parts.empty()) throw InputError("merge: no parts given");
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
