#include "bake/AdaptivePlacement.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <memory>

#include "bake/ProbeValidity.h"
#include "bake/TriangleBoxOverlap.h"
#include "common/Error.h"

namespace baker {
namespace {

// One flag per brick of a level, set from any thread.
class BrickMarks {
 public:
  explicit BrickMarks(std::int64_t bricks) : flags_(new std::atomic<std::uint8_t>[std::size_t(bricks)]()) {}
  void set(std::int64_t brick) { flags_[std::size_t(brick)].store(1, std::memory_order_relaxed); }
  bool operator[](std::int64_t brick) const { return flags_[std::size_t(brick)].load(std::memory_order_relaxed) != 0; }

 private:
  std::unique_ptr<std::atomic<std::uint8_t>[]> flags_;
};

// The box a brick's probes span, grown by `margin` cells on every side.
Eigen::AlignedBox3d brickBox(const ProbeGrid& grid, std::int64_t brick, int margin) {
  const Eigen::Vector3d lo = grid.brickCorner(brick).cast<double>().array() - margin;
  const Eigen::Vector3d hi = (grid.brickCorner(brick) + grid.brickExtent(brick)).cast<double>().array() - 1 + margin;
  return {grid.origin + grid.spacing * lo, grid.origin + grid.spacing * hi};
}

// Marks every brick of `grid` whose grown box the triangle overlaps.
void markTriangle(const ProbeGrid& grid, int margin, const Eigen::Vector3d (&corners)[3], BrickMarks& marks) {
  const Eigen::Vector3i counts = grid.brickCounts();
  Eigen::Vector3i first, last;
  for (int a = 0; a < 3; ++a) {
    const double lo = std::min({corners[0][a], corners[1][a], corners[2][a]});
    const double hi = std::max({corners[0][a], corners[1][a], corners[2][a]});
    // Brick b spans probes [8b - margin, 8b + 7 + margin] along the axis.
    const double from = std::floor(((lo - grid.origin[a]) / grid.spacing - (kBrickSize - 1) - margin) / kBrickSize);
    const double to = std::floor(((hi - grid.origin[a]) / grid.spacing + margin) / kBrickSize);
    if (!(to >= 0.0 && from <= counts[a] - 1.0)) return;  // also a NaN corner
    first[a] = int(std::max(from, 0.0));
    last[a] = int(std::min(to, counts[a] - 1.0));
  }
  for (int bz = first.z(); bz <= last.z(); ++bz)
    for (int by = first.y(); by <= last.y(); ++by)
      for (int bx = first.x(); bx <= last.x(); ++bx) {
        const std::int64_t brick = bx + std::int64_t(counts.x()) * (by + std::int64_t(counts.y()) * bz);
        if (!marks[brick] && triangleOverlapsBox(corners[0], corners[1], corners[2], brickBox(grid, brick, margin)))
          marks.set(brick);
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
  std::int64_t n = 0;
  for (const std::int64_t b : bricks[std::size_t(level)]) n += grids[std::size_t(level)].brickExtent(b).cast<std::int64_t>().prod();
  return n;
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
  const std::vector<std::unique_ptr<BrickMarks>> marks = markGeometry(scene, placement.grids, marginCells);

  const std::int64_t coarseBricks = coarsest.brickCount();
  std::vector<std::uint8_t> dropped(std::size_t(coarseBricks), 0);
  const std::vector<Eigen::Vector3f> directions = validityDirections(ValidityOptions{});
  tbb::parallel_for(std::int64_t(0), coarseBricks, [&](std::int64_t b) {
    dropped[std::size_t(b)] = !(*marks[0])[b] && deepInside(tracer, coarsest, b, directions);
  });
  placement.bricks.resize(std::size_t(levels));
  for (std::int64_t b = 0; b < coarseBricks; ++b) {
    if (dropped[std::size_t(b)]) ++placement.deepInsideBricks;
    else placement.bricks[0].push_back(b);
  }
  for (int level = 1; level < levels; ++level)
    for (std::int64_t b = 0; b < placement.grids[std::size_t(level)].brickCount(); ++b)
      if ((*marks[std::size_t(level)])[b]) placement.bricks[std::size_t(level)].push_back(b);
  if (placement.probes() > maxProbes)
    throw SettingError("spacing", fmt::format("{:.4g} m over {} levels places {} probes; the limit is {} (raise the spacing "
                                              "or lower the levels)",
                                              finest.spacing, levels, placement.probes(), maxProbes));
  return placement;
}

}  // namespace baker
