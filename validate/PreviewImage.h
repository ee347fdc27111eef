#pragma once
#include <Eigen/Core>
#include <optional>
#include <vector>

#include "images/RgbImage.h"
#include "volume/AdaptiveVolume.h"

namespace baker {

// A picture of a volume a person reads at a glance (`baker preview`).
//
// Two rows of three panels, each probe of the finest level's grid a square cell of cellPixels = clamp(256 / largest dimension,
// 4, 32) pixels (a 16³ volume gets 16-pixel cells), 8-pixel margins:
//   row 1: the XZ slice through the middle probe row j = ny/2, seen from above (x to the right,
//          z downwards);
//   row 2: the XY slice through the middle probe layer k = nz/2, seen from +Z (x to the right,
//          y upwards);
//   panels: reconstructed irradiance E towards +Y, E towards −Y, sky visibility V(+Y) in grey
//          (black 0, white 1).
// A cell shows the probe of the finest level holding one at its place (a uniform volume holds
// them all); where no level does, what an engine reads there (the finest level holding the
// probes around it, interpolated: a coarser level's between its probes).
// Invalid probes (filled from their neighbours) carry a red cross, relocated ones a cyan square.
// Below: a colour bar from E = 0 (left) to the largest E shown or, if smaller, the E that shows at
// 90 % of white (right; beyond it colours barely change), through the same exposure and tone
// curve, with ticks under it at the median (long, white) and at powers of ten (short).
// With a probe position, a last row of lat-long spheres in the reference tools' convention
// (validate/ReferencePanoramas.h), each max(128, panel width) × half that: the volume's E(n) there,
// and with a reference panorama its exact E(n) and its radiance × π (the E a uniform sky of that
// radiance gives), all under one exposure.
//
// Colours are display-referred: c = x / (1 + x), x = exposure × E per channel (negative E shows
// black), so nothing clips; the image goes to writeSrgbPng with exposure 1. The automatic
// exposure is 1 / (2 × median of the probes' (R+G+B)/3 over both directions and slices), which
// shows the median at a third of white.
struct PreviewOptions {
  std::optional<double> exposure;
  std::optional<Eigen::Vector3d> probe;
  const RgbImage* referencePanorama = nullptr;  // only with `probe`
};

struct Preview {
  RgbImage image;
  int cellPixels = 0;
  int xzSliceRow = 0;    // j of the XZ slice
  int xySliceLayer = 0;  // k of the XY slice
  double exposure = 1.0;
  double medianIrradiance = 0.0;
  double maxIrradiance = 0.0;  // the largest channel of E shown
  double colourBarEnd = 0.0;   // the E at the right end of the colour bar
  int invalidProbesShown = 0;
  int relocatedProbesShown = 0;
  std::vector<int> cellsByLevel;  // of both slices, by the level their values come from
};

Preview renderPreview(const AdaptiveVolume& volume, const PreviewOptions& options);

}  // namespace baker
