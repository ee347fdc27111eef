#include "cli/PreviewCommand.h"

#include <fmt/format.h>

#include <cmath>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>

#include "cli/CommandLine.h"
#include "common/Error.h"
#include "formats/AtomicFile.h"
#include "formats/VolumeReader.h"
#include "images/RgbImage.h"
#include "validate/PreviewImage.h"
#include "validate/ReferencePanoramas.h"

namespace baker {

namespace {

nlohmann::json previewJson(const std::string& out, const Preview& preview, const PreviewOptions& options,
                           const std::optional<ReferenceProbe>& reference, double sliceY, double sliceZ) {
  nlohmann::json j = {{"out", out},
                      {"width", preview.image.width},
                      {"height", preview.image.height},
                      {"cell_pixels", preview.cellPixels},
                      {"xz_slice", {{"j", preview.xzSliceRow}, {"y", sliceY}}},
                      {"xy_slice", {{"k", preview.xySliceLayer}, {"z", sliceZ}}},
                      {"exposure", preview.exposure},
                      {"median_irradiance", preview.medianIrradiance},
                      {"colour_bar", {0.0, preview.colourBarEnd}},
                      {"max_irradiance", preview.maxIrradiance},
                      {"invalid_probes_shown", preview.invalidProbesShown},
                      {"relocated_probes_shown", preview.relocatedProbesShown},
                      {"cells_by_level", preview.cellsByLevel}};
  if (options.probe) j["probe"] = {options.probe->x(), options.probe->y(), options.probe->z()};
  if (reference)
    j["reference_probe"] = {{"index", reference->index},
                            {"file", reference->file},
                            {"position", {reference->position.x(), reference->position.y(), reference->position.z()}},
                            {"distance", (reference->position - *options.probe).norm()}};
  return j;
}

}  // namespace

int runPreviewCommand(int argc, char** argv) {
  CLI::App app{"Draw a volume as a PNG: its middle slices coloured by irradiance and sky visibility."};
  app.footer(
      "Rows: the XZ slice through the middle probe row (seen from above, x right, z down) and the XY slice through the "
      "middle probe layer (seen from +Z, x right, y up); of an adaptive volume, on its finest level's grid, each cell "
      "the finest level's probe at its place or, where no level holds one, what sampling reads there. Panels: irradiance E towards +Y, towards -Y, sky visibility "
      "V(+Y) in grey. Red cross: invalid probe (filled from neighbours); cyan square: relocated probe. Colour bar: E "
      "from 0 to the largest shown (at most where colours reach 90% of white), ticks at the median (long) and powers of ten. Colours are x/(1+x), x = exposure "
      "x E; automatic exposure 1/(2 x median). --probe adds that position's E(n) as a lat-long sphere (reference "
      "tools' convention); with --reference, the nearest reference probe's exact E(n) and radiance x pi beside it.");
  std::string path, out, probeText, referenceDirectory;
  double exposure = 0.0;
  bool json = false;
  app.add_option("volume", path, "volume (.vdb, or a directory of EXR slices)")->required();
  app.add_option("--out", out, "PNG to write")->required();
  CLI::Option* probeOption = app.add_option("--probe", probeText, "also draw the irradiance sphere at world position x,y,z");
  app.add_option("--reference", referenceDirectory, "reference_probe.py output: show the nearest probe's panorama")
      ->needs(probeOption);
  CLI::Option* exposureOption = app.add_option("--exposure", exposure, "multiplier on E before the tone curve");
  app.add_flag("--json", json, "print the legend as JSON on stdout");
  return runGuarded("baker preview", app, argc, argv, [&]() {
    PreviewOptions options;
    if (exposureOption->count() > 0) {
      if (!std::isfinite(exposure) || exposure <= 0.0)
        throw InputError(fmt::format("--exposure {}: expected a finite number > 0", exposure));
      options.exposure = exposure;
    }
    if (!probeText.empty()) options.probe = parseTriple("--probe", probeText);
    AtomicFile file(out);
    const AdaptiveVolume volume = readLevels(path);

    std::optional<ReferenceProbe> reference;
    RgbImage panorama;
    if (!referenceDirectory.empty()) {
      reference = nearestReferenceProbe(readReferenceSet(referenceDirectory), *options.probe);
      panorama = readRgbImage(reference->file);
      options.referencePanorama = &panorama;
    }
    const Preview preview = renderPreview(volume, options);
    writeSrgbPng(preview.image, 1.0, file.temporaryPath());
    file.commit();

    const ProbeGrid& g = volume.levels.back().grid;  // the slices' grid
    const double sliceY = g.origin.y() + g.spacing * preview.xzSliceRow;
    const double sliceZ = g.origin.z() + g.spacing * preview.xySliceLayer;
    if (json) {
      std::cout << previewJson(out, preview, options, reference, sliceY, sliceZ).dump(2) << "\n";
      return 0;
    }
    std::cout << fmt::format("wrote {} ({} x {} pixels, {} per probe)\n", out, preview.image.width, preview.image.height,
                             preview.cellPixels);
    std::cout << fmt::format("rows: XZ slice at y = {:.4g} (j = {}), XY slice at z = {:.4g} (k = {}); panels: E(+Y), "
                             "E(-Y), sky visibility V(+Y)\n",
                             sliceY, preview.xzSliceRow, sliceZ, preview.xySliceLayer);
    std::cout << fmt::format("colour bar: E from 0 to {:.4g} (largest shown {:.4g}), median {:.4g} (long tick), exposure "
                             "{:.4g}{}\n",
                             preview.colourBarEnd, preview.maxIrradiance, preview.medianIrradiance, preview.exposure,
                             options.exposure ? "" : " (automatic)");
    std::cout << fmt::format("shown: {} invalid probes (red cross), {} relocated (cyan square)\n",
                             preview.invalidProbesShown, preview.relocatedProbesShown);
    if (volume.levels.size() > 1)
      std::cout << fmt::format("levels: cells on the finest level's grid (spacing {:.4g}); their values from levels 0 "
                               "(coarsest) to {}: {}\n",
                               g.spacing, volume.levels.size() - 1, fmt::join(preview.cellsByLevel, ", "));
    if (reference)
      std::cout << fmt::format("reference probe {} at ({:.4g}, {:.4g}, {:.4g}), {:.4g} from --probe: {}\n", reference->index,
                               reference->position.x(), reference->position.y(), reference->position.z(),
                               (reference->position - *options.probe).norm(), reference->file);
    return 0;
  });
}

}  // namespace baker
