#include "validate/PreviewImage.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "formats/VolumeReconstruction.h"
#include "formats/VolumeSampler.h"
#include "validate/DisplayColour.h"
#include "validate/ReferencePanoramas.h"

namespace baker {
namespace {

constexpr int kMargin = 8;
constexpr int kColourBarHeight = 16;
constexpr int kTickHeight = 6;
constexpr int kMinSphereWidth = 128;
const Eigen::Vector3f kBackground(0.05f, 0.05f, 0.05f);
const Eigen::Vector3f kInvalidMark(1.0f, 0.0f, 0.0f);
const Eigen::Vector3f kRelocatedMark(0.0f, 1.0f, 1.0f);
const Eigen::Vector3d kUp(0.0, 1.0, 0.0);

void fillRect(RgbImage& image, int x, int y, int w, int h, const Eigen::Vector3f& colour) {
  for (int row = std::max(y, 0); row < std::min(y + h, image.height); ++row)
    for (int column = std::max(x, 0); column < std::min(x + w, image.width); ++column)
      std::copy(colour.data(), colour.data() + 3, image.pixel(row, column));
}

// The probes of one slice as the panel shows them, row by row from the top.
struct Slice {
  int columns = 0;
  int rows = 0;
  std::vector<std::int64_t> probes;
};

Slice xzSlice(const ProbeGrid& g, int j) {
  Slice s{g.dims.x(), g.dims.z(), {}};
  for (int k = 0; k < g.dims.z(); ++k)
    for (int i = 0; i < g.dims.x(); ++i) s.probes.push_back(g.linearIndex(i, j, k));
  return s;
}

Slice xySlice(const ProbeGrid& g, int k) {
  Slice s{g.dims.x(), g.dims.y(), {}};
  for (int j = g.dims.y() - 1; j >= 0; --j)
    for (int i = 0; i < g.dims.x(); ++i) s.probes.push_back(g.linearIndex(i, j, k));
  return s;
}

// What a slice's probes show: E up and down, and sky visibility up.
struct SliceValues {
  std::vector<Eigen::Vector3f> up, down;
  std::vector<float> skyUp;
};

SliceValues sliceValues(const Volume& v, const VolumeReconstruction& reading, const Slice& s) {
  SliceValues values;
  for (std::int64_t p : s.probes) {
    values.up.push_back(reading.irradiance(v.probe(p), kUp));
    values.down.push_back(reading.irradiance(v.probe(p), -kUp));
    values.skyUp.push_back(v.visibilityPerProbe > 0
                               ? float(reading.skyVisibility(v.visibility.data() + p * v.visibilityPerProbe, kUp))
                               : 0.0f);
  }
  return values;
}

ProbeState stateOf(const Volume& v, std::int64_t p) { return v.states.empty() ? ProbeState::Valid : v.states[p]; }

// Cells of `colours` (one per probe of the slice), with the markers of invalid and relocated probes.
void drawSlice(RgbImage& image, int x0, int y0, int cell, const Volume& v, const Slice& s,
               const std::vector<Eigen::Vector3f>& colours) {
  // A background line between cells large enough to spare it, so that they read as probes.
  const int gap = cell >= 8 ? 1 : 0;
  for (int row = 0; row < s.rows; ++row)
    for (int column = 0; column < s.columns; ++column) {
      const std::size_t q = std::size_t(row) * s.columns + column;
      const int x = x0 + column * cell, y = y0 + row * cell;
      fillRect(image, x, y, cell - gap, cell - gap, colours[q]);
      const ProbeState state = stateOf(v, s.probes[q]);
      if (state == ProbeState::Invalid) {
        const int thickness = cell >= 12 ? 2 : 1;
        for (int t = 0; t < cell - gap; ++t) {
          fillRect(image, x + t, y + t, thickness, 1, kInvalidMark);
          fillRect(image, x + cell - gap - thickness - t, y + t, thickness, 1, kInvalidMark);
        }
      } else if (state == ProbeState::Relocated) {
        const int size = std::max(2, cell / 3);
        fillRect(image, x + (cell - gap - size) / 2, y + (cell - gap - size) / 2, size, size, kRelocatedMark);
      }
    }
}

// E(n) over the lat-long directions of a width × height image.
RgbImage sphereImage(int width, int height, const std::vector<Eigen::Vector3d>& e, double exposure) {
  RgbImage image(width, height);
  for (int row = 0; row < height; ++row)
    for (int column = 0; column < width; ++column) {
      const Eigen::Vector3f c = displayedColour(e[std::size_t(row) * width + column].cast<float>(), exposure);
      std::copy(c.data(), c.data() + 3, image.pixel(row, column));
    }
  return image;
}

void blit(RgbImage& target, const RgbImage& source, int x0, int y0) {
  for (int row = 0; row < source.height; ++row)
    for (int column = 0; column < source.width; ++column)
      std::copy(source.pixel(row, column), source.pixel(row, column) + 3, target.pixel(y0 + row, x0 + column));
}

// The colour bar under the panels: E from 0 to colourBarEnd, ticks at decades and the median.
void drawColourBar(Preview& preview, int barWidth, int barTop) {
  const auto barColumn = [&](double e) { return kMargin + int(std::lround(e / preview.colourBarEnd * (barWidth - 1))); };
  for (int column = 0; column < barWidth; ++column) {
    const double e = barWidth > 1 ? preview.colourBarEnd * column / (barWidth - 1) : 0.0;
    fillRect(preview.image, kMargin + column, barTop, 1, kColourBarHeight,
             displayedColour(Eigen::Vector3f::Constant(float(e)), preview.exposure));
  }
  if (preview.colourBarEnd > 0.0) {
    const double largestDecade = std::pow(10.0, std::floor(std::log10(preview.colourBarEnd)));
    for (double decade = largestDecade; barColumn(decade) > kMargin; decade /= 10.0)
      fillRect(preview.image, barColumn(decade), barTop + kColourBarHeight, 1, kTickHeight / 2,
               Eigen::Vector3f::Constant(0.6f));
    if (preview.medianIrradiance > 0.0 && preview.medianIrradiance <= preview.colourBarEnd)
      fillRect(preview.image, barColumn(preview.medianIrradiance), barTop + kColourBarHeight, 1, kTickHeight,
               Eigen::Vector3f::Ones());
  }

}

// The probe's irradiance sphere, and beside it the reference panorama's irradiance and radiance.
void drawProbeSpheres(Preview& preview, const Volume& volume, const VolumeReconstruction& reading, const PreviewOptions& options,
                      int sphereWidth, int sphereHeight, int sphereTop) {
  std::vector<Eigen::Vector3d> directions;
  for (int row = 0; row < sphereHeight; ++row)
    for (int column = 0; column < sphereWidth; ++column)
      directions.push_back(panoramaDirection(sphereWidth, sphereHeight, column, row));
  const VolumeSample sample = sampleVolume(volume, *options.probe);
  std::vector<Eigen::Vector3d> e;
  for (const Eigen::Vector3d& d : directions) e.push_back(reading.irradiance(sample.coefficients.data(), d).cast<double>());
  blit(preview.image, sphereImage(sphereWidth, sphereHeight, e, preview.exposure), kMargin, sphereTop);
  if (options.referencePanorama) {
    const RgbImage& radiance = *options.referencePanorama;
    blit(preview.image, sphereImage(sphereWidth, sphereHeight, panoramaIrradiance(radiance, directions), preview.exposure),
         2 * kMargin + sphereWidth, sphereTop);
    // Nearest pixel of the panorama under each pixel of the sphere: both share the convention.
    std::vector<Eigen::Vector3d> shown;
    for (int row = 0; row < sphereHeight; ++row)
      for (int column = 0; column < sphereWidth; ++column) {
        const float* l = radiance.pixel(row * radiance.height / sphereHeight, column * radiance.width / sphereWidth);
        shown.push_back(M_PI * Eigen::Vector3d(l[0], l[1], l[2]));
      }
    blit(preview.image, sphereImage(sphereWidth, sphereHeight, shown, preview.exposure), 3 * kMargin + 2 * sphereWidth,
         sphereTop);
  }
}

}  // namespace

Preview renderPreview(const Volume& volume, const PreviewOptions& options) {
  const VolumeReconstruction reading(volume);
  const ProbeGrid& g = volume.grid;
  Preview preview;
  preview.cellPixels = std::clamp(256 / g.dims.maxCoeff(), 4, 32);
  preview.xzSliceRow = g.dims.y() / 2;
  preview.xySliceLayer = g.dims.z() / 2;
  const Slice slices[2] = {xzSlice(g, preview.xzSliceRow), xySlice(g, preview.xySliceLayer)};
  const SliceValues values[2] = {sliceValues(volume, reading, slices[0]), sliceValues(volume, reading, slices[1])};

  std::vector<double> luminance;
  for (const SliceValues& v : values)
    for (const auto* side : {&v.up, &v.down})
      for (const Eigen::Vector3f& e : *side) {
        luminance.push_back(e.mean());
        preview.maxIrradiance = std::max(preview.maxIrradiance, double(e.maxCoeff()));
      }
  preview.medianIrradiance = medianOf(luminance);
  const double typical = preview.medianIrradiance > 0.0 ? preview.medianIrradiance : preview.maxIrradiance;
  preview.exposure = options.exposure ? *options.exposure : typical > 0.0 ? 1.0 / (2.0 * typical) : 1.0;
  // x / (1 + x) = 0.9 at x = 9.
  preview.colourBarEnd = std::min(preview.maxIrradiance, 9.0 / preview.exposure);

  const int cell = preview.cellPixels;
  const int panelWidth = g.dims.x() * cell;
  const int panelHeights[2] = {g.dims.z() * cell, g.dims.y() * cell};
  const int sphereWidth = std::max(kMinSphereWidth, 2 * ((panelWidth + 1) / 2));
  const int sphereHeight = sphereWidth / 2;
  const int spheres = !options.probe ? 0 : options.referencePanorama ? 3 : 1;
  const int width = std::max(kMargin + 3 * (panelWidth + kMargin), kMargin + spheres * (sphereWidth + kMargin));
  const int barTop = kMargin + panelHeights[0] + kMargin + panelHeights[1] + kMargin;
  const int sphereTop = barTop + kColourBarHeight + kTickHeight + kMargin;
  const int height = sphereTop + (spheres > 0 ? sphereHeight + kMargin : 0);
  preview.image = RgbImage(width, height);
  fillRect(preview.image, 0, 0, width, height, kBackground);

  int top = kMargin;
  for (int s = 0; s < 2; ++s) {
    std::vector<Eigen::Vector3f> up, down, sky;
    for (std::size_t q = 0; q < slices[s].probes.size(); ++q) {
      up.push_back(displayedColour(values[s].up[q], preview.exposure));
      down.push_back(displayedColour(values[s].down[q], preview.exposure));
      sky.push_back(Eigen::Vector3f::Constant(std::clamp(values[s].skyUp[q], 0.0f, 1.0f)));
    }
    const std::vector<Eigen::Vector3f>* panels[3] = {&up, &down, &sky};
    for (int panel = 0; panel < 3; ++panel)
      drawSlice(preview.image, kMargin + panel * (panelWidth + kMargin), top, cell, volume, slices[s], *panels[panel]);
    top += panelHeights[s] + kMargin;
    for (std::int64_t p : slices[s].probes) {
      preview.invalidProbesShown += stateOf(volume, p) == ProbeState::Invalid;
      preview.relocatedProbesShown += stateOf(volume, p) == ProbeState::Relocated;
    }
  }

  drawColourBar(preview, 3 * panelWidth + 2 * kMargin, barTop);
  if (options.probe) drawProbeSpheres(preview, volume, reading, options, sphereWidth, sphereHeight, sphereTop);
  return preview;
}

}  // namespace baker
