#include "cli/MergeCommand.h"

#include <fmt/format.h>

#include <iostream>
#include <nlohmann/json.hpp>

#include "cli/CommandLine.h"
#include "common/PeakMemory.h"
#include "formats/PartMerge.h"

namespace baker {

int runMergeCommand(int argc, char** argv) {
  CLI::App app{"Merge the parts of a bake cut into shards (baker SCENE --shard K/N) into the volume one process "
               "would have written, byte for byte."};
  std::string outPath, format, precision = "half";
  std::vector<std::string> parts;
  bool json = false;
  app.add_option("out", outPath, "output volume: a .vdb file or a directory, as for the bake's --out")->required();
  app.add_option("parts", parts, "every part of the bake, once each, in any order (.vdb files or EXR directories)")
      ->required();
  app.add_option("--format", format, "vdb, exr, bevy or threejs; default: from OUT (.vdb: vdb, else exr)");
  app.add_option("--precision", precision, "EXR slices: half or float, as the bake's --precision")->capture_default_str();
  app.add_flag("--json", json, "print the summary as JSON on stdout");
  return runGuarded("baker merge", app, argc, argv, [&]() {
    const VolumeOutput output = volumeOutput("", outPath, format, precision);
    const MergeReport r = mergeParts(parts, output);
    if (json) {
      std::cout << nlohmann::json{{"output", output.path},
                                  {"format", volumeFormatName(output.format)},
                                  {"basis", r.basis},
                                  {"parts", r.shards},
                                  {"levels", r.levels},
                                  {"probes", r.probes},
                                  {"invalid_probes_filled", r.invalidProbes},
                                  {"seconds", {{"read_and_fill", r.readSeconds}, {"write", r.writeSeconds}}},
                                  {"peak_memory_bytes", peakMemoryBytes()}}
                       .dump(2)
                << "\n";
      return 0;
    }
    std::cout << fmt::format("wrote {} ({}, {} probes{}) from {} parts; {} invalid probes filled from their "
                             "neighbours across the whole grid; read and fill {:.2f} s, write {:.2f} s\n",
                             output.path, r.basis, r.probes, r.levels > 1 ? fmt::format(" in {} levels", r.levels) : "",
                             r.shards, r.invalidProbes, r.readSeconds, r.writeSeconds);
    if (!r.engineExport.engine.empty())
      std::cout << fmt::format("  for {}: {}\n", r.engineExport.engine, r.engineExport.conversion);
    return 0;
  });
}

}  // namespace baker
