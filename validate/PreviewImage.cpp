#include "validate/PreviewImage.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "formats/VolumeReconstruction.h"
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

// What one cell of a slice shows: E up and down, sky visibility up, and the state of the probe
// it shows (Valid where it shows a reading between probes).
struct Cell {
  Eigen::Vector3f up, down;
  float skyUp = 0.0f;
  ProbeState state = ProbeState::Valid;
  int level = 0;  // the level its values come from
};

// The cells of one slice as the panel shows them, row by row from the top.
struct Slice {
  int columns = 0;
  int rows = 0;
  std::vector<Cell> cells;
};

// The row of the probe `level` holds at `world`, or -1 when `world` is not one of its lattice
// points or the probe is not held.
std::int64_t rowAt(const Volume& level, const Eigen::Vector3d& world) {
  const Eigen::Vector3d index = (world - level.grid.origin) / level.grid.spacing;
  const Eigen::Vector3d nearest = index.array().round();
  if ((index - nearest).cwiseAbs().maxCoeff() > 1e-6) return -1;
  for (int a = 0; a < 3; ++a)
    if (nearest[a] < 0.0 || nearest[a] >= level.grid.dims[a]) return -1;
  return level.rows.row(level.grid, int(nearest.x()), int(nearest.y()), int(nearest.z()));
}

// A cell at a probe of the finest level's grid: the finest level's probe held there, shown as it
// is; where no level holds one, what an engine reads there (the finest level holding the probes
// around it, interpolated). A uniform volume holds every probe.
Cell readCell(const AdaptiveVolume& volume, const VolumeReconstruction& reading, const Eigen::Vector3d& world) {
  const Volume& coarsest = volume.coarsest();
  const auto shown = [&](const float* coefficients, const float* visibility, int level, ProbeState state) {
    const double sky = coarsest.visibilityPerProbe > 0 ? reading.skyVisibility(visibility, kUp) : 0.0;
    return Cell{reading.irradiance(coefficients, kUp), reading.irradiance(coefficients, -kUp), float(sky), state, level};
  };
  for (int l = int(volume.levels.size()) - 1; l >= 0; --l) {
    const Volume& level = volume.levels[std::size_t(l)];
    const std::int64_t row = rowAt(level, world);
    if (row < 0) continue;
    return shown(level.coefficients.data() + row * level.coefficientsPerProbe,
                 level.visibility.data() + row * level.visibilityPerProbe, l,
                 level.states.empty() ? ProbeState::Valid : level.states[std::size_t(row)]);
  }
  thread_local std::vector<float> coefficients, visibility;
  coefficients.resize(std::size_t(coarsest.coefficientsPerProbe));
  visibility.resize(std::size_t(coarsest.visibilityPerProbe));
  const LevelChoice choice = finestLevelAt(volume.levels, int(volume.levels.size()), world);
  choice.interpolation.apply(volume.levels[std::size_t(choice.level)], !choice.interpolation.complete(),
                             coefficients.data(), visibility.data());
  return shown(coefficients.data(), visibility.data(), choice.level, ProbeState::Valid);
}

Slice xzSlice(const AdaptiveVolume& volume, const VolumeReconstruction& reading, const ProbeGrid& g, int j) {
  Slice s{g.dims.x(), g.dims.z(), {}};
  for (int k = 0; k < g.dims.z(); ++k)
    for (int i = 0; i < g.dims.x(); ++i) s.cells.push_back(readCell(volume, reading, g.position(i, j, k)));
  return s;
}

Slice xySlice(const AdaptiveVolume& volume, const VolumeReconstruction& reading, const ProbeGrid& g, int k) {
  Slice s{g.dims.x(), g.dims.y(), {}};
  for (int j = g.dims.y() - 1; j >= 0; --j)
    for (int i = 0; i < g.dims.x(); ++i) s.cells.push_back(readCell(volume, reading, g.position(i, j, k)));
  return s;
}

// Cells of `colours` (one per cell of the slice), with the markers of invalid and relocated probes.
void drawSlice(RgbImage& image, int x0, int y0, int cell, const Slice& s, const std::vector<Eigen::Vector3f>& colours) {
  // A background line between cells large enough to spare it, so that they read as probes.
  const int gap = cell >= 8 ? 1 : 0;
  for (int row = 0; row < s.rows; ++row)
    for (int column = 0; column < s.columns; ++column) {
      const std::size_t q = std::size_t(row) * s.columns + column;
      const int x = x0 + column * cell, y = y0 + row * cell;
      fillRect(image, x, y, cell - gap, cell - gap, colours[q]);
      const ProbeState state = s.cells[q].state;
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
void drawProbeSpheres(Preview& preview, const AdaptiveVolume& volume, const VolumeReconstruction& reading,
                      const PreviewOptions& options, int sphereWidth, int sphereHeight, int sphereTop) {
  std::vector<Eigen::Vector3d> directions;
  for (int row = 0; row < sphereHeight; ++row)
    for (int column = 0; column < sphereWidth; ++column)
      directions.push_back(panoramaDirection(sphereWidth, sphereHeight, column, row));
  std::vector<float> coefficients(std::size_t(volume.coarsest().coefficientsPerProbe)),
      visibility(std::size_t(volume.coarsest().visibilityPerProbe));
  sampleLevels(volume.levels, int(volume.levels.size()), *options.probe, coefficients.data(), visibility.data());
  std::vector<Eigen::Vector3d> e;
  for (const Eigen::Vector3d& d : directions) e.push_back(reading.irradiance(coefficients.data(), d).cast<double>());
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

Preview renderPreview(const AdaptiveVolume& volume, const PreviewOptions& options) {
  const VolumeReconstruction reading(volume.coarsest());
  const ProbeGrid& g = volume.levels.back().grid;
  Preview preview;
  preview.cellPixels = std::clamp(256 / g.dims.maxCoeff(), 4, 32);
  preview.xzSliceRow = g.dims.y() / 2;
  preview.xySliceLayer = g.dims.z() / 2;
  const Slice slices[2] = {xzSlice(volume, reading, g, preview.xzSliceRow),
                           xySlice(volume, reading, g, preview.xySliceLayer)};

  std::vector<double> luminance;
  preview.cellsByLevel.assign(volume.levels.size(), 0);
  for (const Slice& slice : slices)
    for (const Cell& cell : slice.cells) {
      for (const Eigen::Vector3f& e : {cell.up, cell.down}) {
        luminance.push_back(e.mean());
        preview.maxIrradiance = std::max(preview.maxIrradiance, double(e.maxCoeff()));
      }
      preview.cellsByLevel[std::size_t(cell.level)] += 1;
      preview.invalidProbesShown += cell.state == ProbeState::Invalid;
      preview.relocatedProbesShown += cell.state == ProbeState::Relocated;
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
    for (const Cell& c : slices[s].cells) {
      up.push_back(displayedColour(c.up, preview.exposure));
      down.push_back(displayedColour(c.down, preview.exposure));
      sky.push_back(Eigen::Vector3f::Constant(std::clamp(c.skyUp, 0.0f, 1.0f)));
    }
    const std::vector<Eigen::Vector3f>* panels[3] = {&up, &down, &sky};
    for (int panel = 0; panel < 3; ++panel)
      drawSlice(preview.image, kMargin + panel * (panelWidth + kMargin), top, cell, slices[s], *panels[panel]);
    top += panelHeights[s] + kMargin;
  }

  drawColourBar(preview, 3 * panelWidth + 2 * kMargin, barTop);
  if (options.probe) drawProbeSpheres(preview, volume, reading, options, sphereWidth, sphereHeight, sphereTop);
  return preview;
}

}  // namespace baker
