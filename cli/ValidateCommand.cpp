#include "cli/ValidateCommand.h"

#include <fmt/format.h>

#include <cmath>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>

#include "cli/CommandLine.h"
#include "common/Error.h"
#include "formats/AtomicFile.h"
#include "formats/VolumeReader.h"
#include "relight/Relighting.h"
#include "validate/IrradianceError.h"
#include "validate/ReferenceComparison.h"
#include "validate/ReferencePanoramas.h"
#include "validate/ValidationReport.h"
#include "validate/VolumeComparison.h"

namespace baker {
namespace {

// Enough probes for a person to look at first; the statistics cover them all.
constexpr std::size_t kWorstProbes = 10;

// The box the grid's cells cover, for messages about grids that do not overlap.
std::string coveredRegionText(const ProbeGrid& g) {
  const Eigen::Vector3d lo = g.origin.array() - 0.5 * g.spacing;
  const Eigen::Vector3d hi = g.origin + g.spacing * (g.dims.cast<double>().array() - 0.5).matrix();
  return fmt::format("({:.4g}, {:.4g}, {:.4g})..({:.4g}, {:.4g}, {:.4g})", lo.x(), lo.y(), lo.z(), hi.x(), hi.y(), hi.z());
}

// A report file, claimed before the comparison runs so that a missing directory costs nothing.
struct ReportFile {
  std::string path;
  std::unique_ptr<AtomicFile> file;

  explicit ReportFile(const std::string& finalPath) : path(finalPath) {
    if (!path.empty()) file = std::make_unique<AtomicFile>(path);
  }
  void write(const std::string& text) {
    if (!file) return;
    std::ofstream out(file->temporaryPath());
    out << text;
    out.close();
    if (!out) throw InputError(fmt::format("{}: cannot write", path));
    file->commit();
  }
};

}  // namespace

int runValidateCommand(int argc, char** argv) {
  CLI::App app{
      "Compare a volume with a reference volume (either format, any basis, any overlapping grid) or with "
      "reference_probe.py's radiance panoramas, in reconstructed irradiance E(n)."};
  app.footer(fmt::format(
      "Each probe of the reference (every level's, for an adaptive volume) is compared at 26 normals: the {}. With the "
      "same grid the new volume's probe of the same level and index is used, otherwise (or where the new volume does not "
      "hold it) the new volume read at the reference probe's position as sampling reads it (reference probes outside the "
      "new volume's cells are skipped). Validity (probe_state) and, for adaptive volumes on the same grids, which "
      "probes each level holds must not change; metadata "
      "differences are reported only.\n"
      "--run-time-env / --run-time-sky: NEW is read as decoders relight it at run time under that sky (its light less "
      "its sky_direct grids, plus the sky's irradiance from its SH to band 2 times NEW's sky visibility V(n)), to "
      "measure that against a rebake under the sky (docs/RELIGHTING.md).\n"
      "--against-reference DIR: DIR is what reference_probe.py writes (probes.json, probe_NNNN.exr); E(n) is the exact "
      "sum over the panorama's pixels. The panoramas contain no punctual light seen directly: bake with "
      "--no direct-punctual for this.\n"
      "Exit 0: every check passed; 1: a check failed; 2: unusable input.",
      kRelativeErrorDefinition));
  std::string referencePath, newPath, referenceDirectory, reportPath, junitPath;
  double tolerance = 0.02;
  bool json = false;
  app.add_option("reference", referencePath, "REFERENCE volume (.vdb or EXR slices), or VOLUME with --against-reference")
      ->required();
  app.add_option("new", newPath, "NEW volume to check against REFERENCE");
  app.add_option("--against-reference", referenceDirectory, "compare VOLUME with reference_probe.py's output DIR");
  SceneOptions runTimeSky;
  app.add_option("--run-time-env", runTimeSky.environmentMap,
                 "read NEW relit at run time, as decoders do, under this lat-long map (.hdr/.exr)");
  app.add_option("--run-time-sky", runTimeSky.sky, "read NEW relit at run time under a constant sky r,g,b");
  app.add_option("--tolerance", tolerance, "largest relative error that passes (default 0.02)");
  app.add_option("--report", reportPath, "write the report as JSON to this file");
  app.add_option("--junit", junitPath, "write the checks as JUnit XML to this file");
  app.add_flag("--json", json, "print the report as JSON on stdout instead of the summary");
  return runGuarded("baker validate", app, argc, argv, [&]() {
    if (referenceDirectory.empty() == newPath.empty())
      throw InputError("expected REFERENCE NEW, or VOLUME --against-reference DIR");
    const bool atRunTime = !runTimeSky.environmentMap.empty() || !runTimeSky.sky.empty();
    if (!runTimeSky.environmentMap.empty() && !runTimeSky.sky.empty())
      throw InputError("--run-time-env and --run-time-sky: give one sky");
    if (atRunTime && !referenceDirectory.empty())
      throw InputError("--run-time-env and --run-time-sky read NEW relit at run time; they do not apply to "
                       "--against-reference");
    if (!std::isfinite(tolerance) || tolerance < 0.0)
      throw InputError(fmt::format("--tolerance {}: expected a finite number >= 0", tolerance));
    ReportFile report(reportPath), junit(junitPath);

    ValidationReport result;
    if (!referenceDirectory.empty()) {
      const AdaptiveVolume volume = readLevels(referencePath);
      const ReferenceSet references = readReferenceSet(referenceDirectory);
      const ReferenceComparison comparison = compareWithReference(volume, references, kWorstProbes);
      if (comparison.probesCompared == 0)
        throw InputError(fmt::format("{}/probes.json: no reference probe lies inside {}'s cells {}", referenceDirectory,
                                     referencePath, coveredRegionText(volume.coarsest().grid)));
      result = referenceValidationReport(comparison, referenceDirectory, referencePath, tolerance);
    } else {
      const AdaptiveVolume reference = readLevels(referencePath);
      const AdaptiveVolume candidate = readLevels(newPath);
      std::optional<DescribedSkyHarmonics> sky;
      std::vector<std::string> warnings;
      if (atRunTime) sky = skyHarmonicsOf(runTimeSky, warnings);
      for (const std::string& w : warnings) std::cerr << "baker validate: warning: " << w << "\n";
      const VolumeComparison comparison =
          compareVolumes(reference, candidate, kWorstProbes, {sky ? &sky->harmonics : nullptr, newPath});
      if (comparison.probesCompared == 0)
        throw InputError(fmt::format("{}: its grid {} does not overlap {}'s {}", newPath, coveredRegionText(candidate.coarsest().grid),
                                     referencePath, coveredRegionText(reference.coarsest().grid)));
      result = volumeValidationReport(comparison, referencePath, newPath, tolerance);
      if (sky) result.json["run_time_sky"] = sky->description;
    }

    report.write(result.json.dump(2) + "\n");
    junit.write(junitXml(result));
    std::cout << (json ? result.json.dump(2) + "\n" : textSummary(result));
    return result.passed() ? 0 : 1;
  });
}

}  // namespace baker
