#pragma once
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>

namespace baker {

// Probes are baked and stored in bricks of kBrickSize³: the unit of parallel work and an
// OpenVDB leaf.
constexpr int kBrickSize = 8;
// Probes along one axis of any grid: far beyond a bake, and brick arithmetic stays in int.
constexpr int kMaxProbesPerAxis = 1 << 24;

// Probes on a uniform grid: probe (i,j,k) sits at origin + spacing·(i,j,k).
struct ProbeGrid {
  Eigen::Vector3i dims{1, 1, 1};
  Eigen::Vector3d origin{0, 0, 0};
  double spacing = 1.0;

  std::int64_t probeCount() const { return std::int64_t(dims.x()) * dims.y() * dims.z(); }
  std::int64_t linearIndex(int i, int j, int k) const { return i + std::int64_t(dims.x()) * (j + std::int64_t(dims.y()) * k); }
  Eigen::Vector3d position(int i, int j, int k) const { return origin + spacing * Eigen::Vector3d(i, j, k); }
  // (i, j, k) of linear index p, and its position.
  Eigen::Vector3i indexOf(std::int64_t p) const {
    return {int(p % dims.x()), int(p / dims.x() % dims.y()), int(p / (std::int64_t(dims.x()) * dims.y()))};
  }
  Eigen::Vector3d position(std::int64_t p) const {
    const Eigen::Vector3i index = indexOf(p);
    return position(index.x(), index.y(), index.z());
  }
  // Bricks per axis, the last one on each axis possibly partial.
  Eigen::Vector3i brickCounts() const { return (dims.array() + kBrickSize - 1) / kBrickSize; }
  std::int64_t brickCount() const { return brickCounts().cast<std::int64_t>().prod(); }
  // Brick `brick` (linear brick index bx + Bx·(by + By·bz)): its first probe, and how many
  // probes it holds per axis (fewer than kBrickSize in the last brick of an axis).
  Eigen::Vector3i brickCorner(std::int64_t brick) const {
    const Eigen::Vector3i b = brickCounts();
    return kBrickSize * Eigen::Vector3i(int(brick % b.x()), int(brick / b.x() % b.y()),
                                        int(brick / (std::int64_t(b.x()) * b.y())));
  }
  Eigen::Vector3i brickExtent(std::int64_t brick) const {
    const Eigen::Vector3i lo = brickCorner(brick);
    return (lo.array() + kBrickSize).min(dims.array()) - lo.array();
  }
  std::int64_t brickOf(int i, int j, int k) const {
    const Eigen::Vector3i b = brickCounts();
    return i / kBrickSize + std::int64_t(b.x()) * (j / kBrickSize + std::int64_t(b.y()) * (k / kBrickSize));
  }
};

// The default spacing aims for this many probes along the longest side of a small scene...
constexpr int kDefaultProbesAlongLongestSide = 16;
// ...and is never wider than this (metres): what engines default to, and what a level designer
// accepts in a scene larger than a room.
constexpr double kDefaultMaxSpacing = 1.0;

// The default spacing for a scene of these bounds: its longest side / 16, at most 1 m.
double defaultSpacing(const Eigen::AlignedBox3f& bounds);

// Probes per axis a grid of `spacing` over `bounds` has (as makeProbeGrid lays it out), as
// doubles so that no spacing overflows them.
Eigen::Vector3d probesPerAxis(const Eigen::AlignedBox3f& bounds, double spacing);

// Cells of `spacing` covering `bounds`, one probe at each cell centre, the whole grid centred
// on the bounds: probes stay half a cell away from the outer walls of a closed room. An axis
// along which the scene is flat gets two probes, half a cell to either side of it.
// spacing <= 0 picks defaultSpacing. An empty scene gets a single probe at the origin.
// Throws InputError if the grid would exceed `maxProbes`.
ProbeGrid makeProbeGrid(const Eigen::AlignedBox3f& bounds, double spacing, std::int64_t maxProbes);

}  // namespace baker
