#include "bake/AdaptivePlacement.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <memory>
#include <stdexcept>

#include "bake/ProbeValidity.h"
#include "bake/TriangleBoxOverlap.h"
#include "common/Error.h"

namespace baker {
namespace {

// Per brick of a level, the sub-bricks some triangle lies near, set from any thread.
class BrickMarks {
 public:
  explicit BrickMarks(std::int64_t bricks) : masks_(new std::atomic<std::uint8_t>[std::size_t(bricks)]()) {}
  void set(std::int64_t brick, std::uint8_t bit) { masks_[std::size_t(brick)].fetch_or(bit, std::memory_order_relaxed); }
  std::uint8_t operator[](std::int64_t brick) const { return masks_[std::size_t(brick)].load(std::memory_order_relaxed); }

 private:
  std::unique_ptr<std::atomic<std::uint8_t>[]> masks_;
};

// The box the probes of sub-brick `s` (whole sub-brick coordinates) span, grown by `margin`
// cells on every side.
Eigen::AlignedBox3d subBrickBox(const ProbeGrid& grid, const Eigen::Vector3i& s, int margin) {
  const Eigen::Vector3i first = kSubBrickSize * s;
  const Eigen::Vector3i last = (first.array() + kSubBrickSize - 1).min(grid.dims.array() - 1);
  const Eigen::Vector3d lo = first.cast<double>().array() - margin, hi = last.cast<double>().array() + margin;
  return {grid.origin + grid.spacing * lo, grid.origin + grid.spacing * hi};
}

// Marks every sub-brick of `grid` whose grown box the triangle overlaps.
void markTriangle(const ProbeGrid& grid, int margin, const Eigen::Vector3d (&corners)[3], BrickMarks& marks) {
  const Eigen::Vector3i counts = (grid.dims.array() + kSubBrickSize - 1) / kSubBrickSize;
  Eigen::Vector3i first, last;
  for (int a = 0; a < 3; ++a) {
    const double lo = std::min({corners[0][a], corners[1][a], corners[2][a]});
    const double hi = std::max({corners[0][a], corners[1][a], corners[2][a]});
    // Sub-brick s spans probes [4s - margin, 4s + 3 + margin] along the axis.
    const double from = std::floor(((lo - grid.origin[a]) / grid.spacing - (kSubBrickSize - 1) - margin) / kSubBrickSize);
    const double to = std::floor(((hi - grid.origin[a]) / grid.spacing + margin) / kSubBrickSize);
    if (!(to >= 0.0 && from <= counts[a] - 1.0)) return;  // also a NaN corner
    first[a] = int(std::max(from, 0.0));
    last[a] = int(std::min(to, counts[a] - 1.0));
  }
  for (int sz = first.z(); sz <= last.z(); ++sz)
    for (int sy = first.y(); sy <= last.y(); ++sy)
      for (int sx = first.x(); sx <= last.x(); ++sx) {
        const Eigen::Vector3i s(sx, sy, sz), probe = kSubBrickSize * s;
        const std::int64_t brick = grid.brickOf(probe.x(), probe.y(), probe.z());
        const std::uint8_t bit = subBrickBit(probe.x(), probe.y(), probe.z());
        if (!(marks[brick] & bit) && triangleOverlapsBox(corners[0], corners[1], corners[2], subBrickBox(grid, s, margin)))
          marks.set(brick, bit);
      }
}

// Per level, the bricks some triangle of the scene lies near.
std::vector<std::unique_ptr<BrickMarks>> markGeometry(const Scene& scene, const std::vector<ProbeGrid>& grids,
                                                      int margin) {
  std::vector<std::unique_ptr<BrickMarks>> marks;
  for (const ProbeGrid& grid : grids) marks.push_back(std::make_unique<BrickMarks>(grid.brickCount()));
  tbb::parallel_for(std::size_t(0), scene.instances.size(), [&](std::size_t i) {
    const Instance& instance = scene.instances[i];
    const Mesh& mesh = scene.meshes[instance.mesh];
    const Eigen::Matrix4d toWorld = instance.objectToWorld.cast<double>();
    tbb::parallel_for(std::size_t(0), mesh.triangles.size(), [&](std::size_t t) {
      Eigen::Vector3d corners[3];
      for (int c = 0; c < 3; ++c)
        corners[c] = (toWorld * mesh.positions[std::size_t(mesh.triangles[t][c])].cast<double>().homogeneous()).head<3>();
      for (std::size_t level = 0; level < grids.size(); ++level) markTriangle(grids[level], margin, corners, *marks[level]);
    });
  });
  return marks;
}

// Whether the centre of a level-0 brick that no triangle lies near is inside closed geometry.
bool deepInside(const RayTracer& tracer, const ProbeGrid& grid, std::int64_t brick,
                const std::vector<Eigen::Vector3f>& directions) {
  const Eigen::Vector3d centre =
      grid.origin + grid.spacing * (grid.brickCorner(brick).cast<double>() + 0.5 * (grid.brickExtent(brick).cast<double>().array() - 1.0).matrix());
  ValidityOptions test;
  test.maxBackfaceRatio = kDeepInsideBackfaceRatio;
  test.maxOffsetFraction = 0.0f;  // a test only: no move
  return placeProbe(tracer, centre.cast<float>(), float(grid.spacing), directions, test, nullptr).backfaceRatio >
         kDeepInsideBackfaceRatio;
}

}  // namespace

std::int64_t AdaptivePlacement::probes(int level) const {
  const ProbeRows held = rows(level);
  std::int64_t n = 0;
  for (const std::int64_t b : bricks[std::size_t(level)]) n += held.probesHeld(grids[std::size_t(level)], b);
  return n;
}

ProbeRows AdaptivePlacement::rows(int level) const {
  return ProbeRows(grids[std::size_t(level)], bricks[std::size_t(level)], masks[std::size_t(level)]);
}

ProbeRows AdaptivePlacement::rows(int level, const std::vector<std::int64_t>& share) const {
  const std::vector<std::int64_t>& placed = bricks[std::size_t(level)];
  std::vector<std::uint8_t> shareMasks;
  shareMasks.reserve(share.size());
  for (const std::int64_t b : share) {
    const auto at = std::lower_bound(placed.begin(), placed.end(), b);
    if (at == placed.end() || *at != b) throw std::logic_error("AdaptivePlacement: a share's brick is not placed");
    shareMasks.push_back(masks[std::size_t(level)][std::size_t(at - placed.begin())]);
  }
  return ProbeRows(grids[std::size_t(level)], share, shareMasks);
}

std::int64_t AdaptivePlacement::probes() const {
  std::int64_t n = 0;
  for (int level = 0; level < levels(); ++level) n += probes(level);
  return n;
}

AdaptivePlacement placeAdaptive(const Scene& scene, const RayTracer& tracer, const ProbeGrid& finest, int levels,
                                int marginCells, std::int64_t maxProbes) {
  AdaptivePlacement placement;
  placement.grids = levelGrids(finest, levels);
  placement.marginCells = marginCells;
  const ProbeGrid& coarsest = placement.grids.front();
  if (double(finest.brickCount()) > kMaxLevelBricks)
    throw SettingError("spacing", fmt::format("{:.4g} m gives {} bricks at the finest level, beyond the {:.3g} an adaptive bake "
                                              "indexes (raise the spacing)",
                                              finest.spacing, finest.brickCount(), kMaxLevelBricks));
  // One cell more than the margin: the neighbours of a probe within the margin are placed too.
  const std::vector<std::unique_ptr<BrickMarks>> marks = markGeometry(scene, placement.grids, marginCells + 1);

  const std::int64_t coarseBricks = coarsest.brickCount();
  std::vector<std::uint8_t> dropped(std::size_t(coarseBricks), 0);
  const std::vector<Eigen::Vector3f> directions = validityDirections(ValidityOptions{});
  tbb::parallel_for(std::int64_t(0), coarseBricks, [&](std::int64_t b) {
    dropped[std::size_t(b)] = (*marks[0])[b] == 0 && deepInside(tracer, coarsest, b, directions);
  });
  placement.bricks.resize(std::size_t(levels));
  placement.masks.resize(std::size_t(levels));
  for (std::int64_t b = 0; b < coarseBricks; ++b) {
    if (dropped[std::size_t(b)]) {
      ++placement.deepInsideBricks;
    } else {
      placement.bricks[0].push_back(b);
      placement.masks[0].push_back(subBricksInGrid(coarsest, b));
    }
  }
  for (std::size_t level = 1; level < std::size_t(levels); ++level) {
    const ProbeGrid& grid = placement.grids[level];
    for (std::int64_t b = 0; b < grid.brickCount(); ++b)
      if (const std::uint8_t mask = std::uint8_t((*marks[level])[b] & subBricksInGrid(grid, b))) {
        placement.bricks[level].push_back(b);
        placement.masks[level].push_back(mask);
      }
  }
  if (placement.probes() > maxProbes)
    throw SettingError("spacing", fmt::format("{:.4g} m over {} levels places {} probes; the limit is {} (raise the spacing "
                                              "or lower the levels)",
                                              finest.spacing, levels, placement.probes(), maxProbes));
  return placement;
}

}  // namespace baker
