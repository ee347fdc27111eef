#include "validate/SurfaceView.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <atomic>
#include <cmath>
#include <stdexcept>

#include "bake/ProbeBaker.h"
#include "bake/RayOffset.h"
#include "common/Error.h"
#include "formats/VolumeReconstruction.h"
#include "formats/VolumeSampler.h"
#include "validate/DisplayColour.h"

namespace baker {
namespace {

const Eigen::Vector3f kNothingSeen(0.05f, 0.05f, 0.05f);
constexpr int kPanelGap = 4;
constexpr std::size_t kPointsPerTask = 64;
// One set of fixed directions for every pixel would draw its aliasing as streaks across the
// picture (a lattice direction that grazes a lamp does so along a line of points): neighbouring
// pixels trace differently turned sets, as a grid's neighbouring probes do, the turn scrambled.
constexpr int kRotations = 8;
int rotationOf(std::size_t pixel) {
  std::uint64_t x = std::uint64_t(pixel) * 0x9E3779B97F4A7C15ull;  // splitmix64's finaliser
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return int((x ^ (x >> 31)) >> 61);
}

double meanChannel(const Eigen::Vector3f& e) { return (double(e.x()) + e.y() + e.z()) / 3.0; }

struct CameraFrame {
  Eigen::Vector3d forward, right, up;
  double halfHeight, halfWidth;
};

CameraFrame frameOf(const SurfaceCamera& camera) {
  CameraFrame f;
  f.forward = (camera.target - camera.eye).normalized();
  const Eigen::Vector3d worldUp = std::abs(f.forward.y()) > 0.999 ? Eigen::Vector3d::UnitZ() : Eigen::Vector3d::UnitY();
  f.right = f.forward.cross(worldUp).normalized();
  f.up = f.right.cross(f.forward);
  f.halfHeight = std::tan(camera.verticalFovDegrees * M_PI / 360.0);
  f.halfWidth = f.halfHeight * camera.width / camera.height;
  return f;
}

// Two neighbouring pixels lie on one plane: the same normal, and the step between them in it.
bool onOnePlane(const SeenPoint& a, const SeenPoint& b) {
  if (!a.seen || !b.seen || a.normal.dot(b.normal) < 0.9999) return false;
  const Eigen::Vector3d step = b.point - a.point;
  return std::abs(a.normal.dot(step)) <= 0.01 * step.norm();
}

// A seam is a step that stands out from the steps beside it: over 2 % of the level and over three
// times either neighbouring step along the same line, all four pixels on one plane. A smooth
// reading (trilinear, or leak-aware weights that change gradually) steps evenly however steep
// its gradient; a single odd pixel is flanked by its own two steps, so it counts as a blotch or
// a leak, not a seam.
void countSeams(const std::vector<SeenPoint>& points, const std::vector<Eigen::Vector3f>& read, int width,
                double level, SurfaceError& error) {
  const std::size_t w = std::size_t(width), rows = points.size() / w;
  std::int64_t seams = 0;
  for (std::size_t row = 0; row < rows; ++row)
    for (std::size_t column = 0; column < w; ++column)
      for (const bool across : {true, false}) {
        const std::size_t line = across ? column : row, length = across ? w : rows, stride = across ? 1 : w;
        if (line == 0 || line + 2 >= length) continue;
        const std::size_t p = row * w + column, a = p - stride, q = p + stride, b = q + stride;
        if (!onOnePlane(points[a], points[p]) || !onOnePlane(points[p], points[q]) || !onOnePlane(points[q], points[b]))
          continue;
        ++error.planePairs;
        const double step = std::abs(meanChannel(read[q]) - meanChannel(read[p]));
        const double flank = std::max(std::abs(meanChannel(read[p]) - meanChannel(read[a])),
                                      std::abs(meanChannel(read[b]) - meanChannel(read[q])));
        if (step > 0.02 * level && step > 3.0 * flank) {
          ++seams;
          error.largestStep = std::max(error.largestStep, step / level);
        }
      }
  error.seams = error.planePairs > 0 ? double(seams) / double(error.planePairs) : 0.0;
}

}  // namespace

std::vector<SeenPoint> surfacesSeen(const RayTracer& tracer, const SurfaceCamera& camera) {
  if (camera.width < 1 || camera.height < 1 || !((camera.target - camera.eye).norm() > 0.0) ||
      !(camera.verticalFovDegrees > 0.0 && camera.verticalFovDegrees < 180.0))
    throw std::invalid_argument("surfacesSeen: a camera needs pixels, a direction and a field of view below 180°");
  const CameraFrame f = frameOf(camera);
  const std::size_t pixels = std::size_t(camera.width) * camera.height;
  std::vector<SeenPoint> points(pixels);
  const Eigen::Vector3f eye = camera.eye.cast<float>();
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, pixels, 8), [&](const tbb::blocked_range<std::size_t>& range) {
    for (std::size_t first = range.begin(); first < range.end(); first += 8) {
      const int count = int(std::min<std::size_t>(8, range.end() - first));
      Eigen::Vector3f directions[8];
      for (int k = 0; k < count; ++k) {
        const std::size_t p = first + k;
        const double x = (2.0 * (double(p % camera.width) + 0.5) / camera.width - 1.0) * f.halfWidth;
        const double y = (1.0 - 2.0 * (double(p / camera.width) + 0.5) / camera.height) * f.halfHeight;
        directions[k] = (f.forward + x * f.right + y * f.up).normalized().cast<float>();
      }
      Hit hits[8];
      tracer.intersect8(eye, directions, count, hits);
      for (int k = 0; k < count; ++k) {
        if (hits[k].missed() || hits[k].frontNormal.squaredNorm() == 0.0f) continue;
        SeenPoint& s = points[first + k];
        s.seen = true;
        s.point = (eye + hits[k].distance * directions[k]).cast<double>();
        s.normal = hits[k].frontNormal.cast<double>().normalized();
        if (s.normal.dot(directions[k].cast<double>()) > 0.0) s.normal = -s.normal;
      }
    }
  });
  return points;
}

std::vector<Eigen::Vector3f> tracedIrradiance(const BakeJob& job, const std::vector<SeenPoint>& points,
                                              std::uint64_t firstId,
                                              const std::function<void(std::int64_t, std::int64_t)>& progress) {
  const ProbeBaker probeBaker(job.scene(), job.tracer(), job.basis(), job.settings(), kRotations);
  const float sceneScale = job.scene().bounds.isEmpty() ? 1.0f : job.scene().bounds.diagonal().norm();
  std::vector<Eigen::Vector3f> irradiance(points.size(), Eigen::Vector3f::Zero());
  std::atomic<std::int64_t> done{0};
  const std::size_t tasks = (points.size() + kPointsPerTask - 1) / kPointsPerTask;
  tbb::parallel_for(std::size_t(0), tasks, [&](std::size_t t) {
    const std::size_t begin = t * kPointsPerTask, end = std::min(points.size(), begin + kPointsPerTask);
    std::vector<ProbeTask> probes;
    std::vector<std::size_t> pixels;
    for (std::size_t p = begin; p < end; ++p) {
      if (!points[p].seen) continue;
      // Just off the surface, far enough that its own triangle does not shadow its upper half.
      const Eigen::Vector3f at = points[p].point.cast<float>();
      const float lift = std::max(1e-4f * sceneScale, surfaceRayOffset(at, sceneScale));
      probes.push_back({at + lift * points[p].normal.cast<float>(), firstId + p, rotationOf(p)});
      pixels.push_back(p);
    }
    if (!probes.empty()) {
      std::vector<float> coefficients(probes.size() * probeBaker.coefficientsPerProbe());
      std::vector<float> visibility(probes.size() * probeBaker.visibilityPerProbe());
      std::vector<ProbeSamples> samples;
      RayCounts counts;
      probeBaker.bake(probes, coefficients.data(), visibility.data(), &counts, &samples);
      for (std::size_t i = 0; i < pixels.size(); ++i) {
        irradiance[pixels[i]] = sampledIrradiance(samples[i], points[pixels[i]].normal.cast<float>());
        if (!irradiance[pixels[i]].allFinite())
          throw NumericalError("a point's traced irradiance is not finite: the scene's radiance overflows float");
      }
    }
    const std::int64_t now = done.fetch_add(std::int64_t(end - begin)) + std::int64_t(end - begin);
    if (progress) progress(now, std::int64_t(points.size()));
  });
  return irradiance;
}

std::vector<Eigen::Vector3f> volumeIrradiance(const AdaptiveVolume& levels, const std::vector<SeenPoint>& points,
                                              bool leakAware, const std::string& source) {
  const VolumeReconstruction reading(levels.coarsest());
  std::vector<Eigen::Vector3f> irradiance(points.size(), Eigen::Vector3f::Zero());
  tbb::parallel_for(std::size_t(0), points.size(), [&](std::size_t p) {
    if (!points[p].seen) return;
    const SurfaceReading s = sampleOnSurface(levels, points[p].point, points[p].normal, leakAware, source);
    irradiance[p] = reading.irradiance(s.coefficients.data(), points[p].normal);
  });
  return irradiance;
}

double surfaceLevel(const std::vector<SeenPoint>& points, const std::vector<Eigen::Vector3f>& values) {
  std::vector<double> seen;
  for (std::size_t p = 0; p < points.size(); ++p)
    if (points[p].seen) seen.push_back(meanChannel(values[p]));
  return medianOf(std::move(seen));
}

SurfaceError compareSurfaces(const std::vector<SeenPoint>& points, const std::vector<Eigen::Vector3f>& read,
                             const std::vector<Eigen::Vector3f>& traced, int width, double level) {
  SurfaceError error;
  if (!(level > 0.0)) return error;
  std::vector<double> errors;
  std::int64_t lit = 0, dark = 0, leaks = 0;
  for (std::size_t p = 0; p < points.size(); ++p) {
    if (!points[p].seen) continue;
    const double r = meanChannel(read[p]), t = meanChannel(traced[p]);
    errors.push_back(std::abs(r - t) / level);
    if (t >= 0.25 * level) {
      ++lit;
      if (r < 0.5 * t) ++dark;
    }
    if (r - t > 0.25 * level) ++leaks;
  }
  countSeams(points, read, width, level, error);
  if (errors.empty()) return error;
  double sum = 0.0;
  for (const double e : errors) sum += e;
  error.meanError = sum / double(errors.size());
  std::sort(errors.begin(), errors.end());
  // Nearest rank: the smallest error at least 95 % of the pixels do not exceed.
  const std::size_t rank = std::size_t(std::ceil(0.95 * double(errors.size())));
  error.p95Error = errors[std::max<std::size_t>(rank, 1) - 1];
  error.darkBlotches = lit > 0 ? double(dark) / double(lit) : 0.0;
  error.leaks = double(leaks) / double(errors.size());
  return error;
}

RgbImage surfacePanels(const std::vector<SeenPoint>& points, const std::vector<std::vector<Eigen::Vector3f>>& panels,
                       int width, int height, double exposure) {
  const int count = int(panels.size());
  RgbImage image(count * width + (count - 1) * kPanelGap, height);
  for (int panel = 0; panel < count; ++panel)
    for (int row = 0; row < height; ++row)
      for (int column = 0; column < width; ++column) {
        const std::size_t p = std::size_t(row) * width + column;
        const Eigen::Vector3f c = points[p].seen ? displayedColour(panels[std::size_t(panel)][p], exposure) : kNothingSeen;
        std::copy(c.data(), c.data() + 3, image.pixel(row, panel * (width + kPanelGap) + column));
      }
  return image;
}

}  // namespace baker
