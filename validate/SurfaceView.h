#pragma once
#include <Eigen/Core>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "bake/BakeJob.h"
#include "images/RgbImage.h"
#include "scene/RayTracer.h"
#include "volume/AdaptiveVolume.h"

namespace baker {

// What a scene's surfaces look like lit by a volume, as an engine shades them, beside the same
// surfaces' own traced irradiance (`baker render`): where a volume leaks light through a wall,
// darkens a lit room with probes from beyond it, or where leak-aware weights leave seams.

// A pinhole camera: `up` is +Y (or +Z when looking straight up or down).
struct SurfaceCamera {
  Eigen::Vector3d eye{0.0, 0.0, 0.0}, target{0.0, 0.0, -1.0};
  double verticalFovDegrees = 60.0;
  int width = 320, height = 240;
};

// The first surface a pixel sees: the point, and the unit normal of the side facing the eye.
struct SeenPoint {
  bool seen = false;
  Eigen::Vector3d point{0.0, 0.0, 0.0}, normal{0.0, 0.0, 1.0};
};

// Rows from the top, pixels left to right.
std::vector<SeenPoint> surfacesSeen(const RayTracer& tracer, const SurfaceCamera& camera);

// Each seen point's irradiance for its normal from its own rays: a probe there, traced with the
// job's settings (ids from `firstId` in pixel order, so that every point draws its own samples),
// its samples' cosine sum (sampledIrradiance), no basis in between. `progress` hears (points
// done, points in all) from worker threads. Zero for pixels that see no surface.
std::vector<Eigen::Vector3f> tracedIrradiance(const BakeJob& job, const std::vector<SeenPoint>& points,
                                              std::uint64_t firstId,
                                              const std::function<void(std::int64_t, std::int64_t)>& progress = {});

// Each seen point's irradiance read from a volume as `baker sample` reads it (sampleOnSurface:
// trilinear or leak-aware). `source` names the volume in errors.
std::vector<Eigen::Vector3f> volumeIrradiance(const AdaptiveVolume& levels, const std::vector<SeenPoint>& points,
                                              bool leakAware, const std::string& source);

// How far a picture read from a volume is from the traced one, in shares of `level` (a room no
// light reaches has none of its own: the caller says what its errors are shares of):
//  - meanError, p95Error: of |read − traced| per pixel (channel mean);
//  - darkBlotches: share of lit pixels (traced ≥ a quarter of the level) read below half their
//    traced value;
//  - leaks: share of seen pixels read brighter than traced by more than a quarter of the level;
//  - seams: of neighbouring pixel pairs on one plane with a neighbour on one plane either side
//    along the same line (planePairs), the share whose readings step by over 2 % of the level
//    and by over three times either flanking step: a jump where the reading should be smooth,
//    found at any resolution and gradient; largestStep is the largest of them.
struct SurfaceError {
  double meanError = 0.0, p95Error = 0.0, darkBlotches = 0.0, leaks = 0.0, seams = 0.0, largestStep = 0.0;
  std::int64_t planePairs = 0;
};
// The median over seen pixels of (R+G+B)/3.
double surfaceLevel(const std::vector<SeenPoint>& points, const std::vector<Eigen::Vector3f>& values);
SurfaceError compareSurfaces(const std::vector<SeenPoint>& points, const std::vector<Eigen::Vector3f>& read,
                             const std::vector<Eigen::Vector3f>& traced, int width, double level);

// The panels side by side, 4 dark pixels apart, in displayedColour at one exposure; pixels that
// see no surface are dark grey.
RgbImage surfacePanels(const std::vector<SeenPoint>& points, const std::vector<std::vector<Eigen::Vector3f>>& panels,
                       int width, int height, double exposure);

}  // namespace baker
