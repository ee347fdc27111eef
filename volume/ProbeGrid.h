#pragma once
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>

namespace baker {

// Probes are baked and stored in bricks of kBrickSize³: the unit of parallel work and an
// OpenVDB leaf.
constexpr int kBrickSize = 8;

// Probes on a uniform grid: probe (i,j,k) sits at origin + spacing·(i,j,k).
struct ProbeGrid {
  Eigen::Vector3i dims{1, 1, 1};
  Eigen::Vector3d origin{0, 0, 0};
  double spacing = 1.0;

  std::int64_t probeCount() const { return std::int64_t(dims.x()) * dims.y() * dims.z(); }
  std::int64_t linearIndex(int i, int j, int k) const { return i + std::int64_t(dims.x()) * (j + std::int64_t(dims.y()) * k); }
  Eigen::Vector3d position(int i, int j, int k) const { return origin + spacing * Eigen::Vector3d(i, j, k); }
  // Bricks per axis, the last one on each axis possibly partial.
  Eigen::Vector3i brickCounts() const { return (dims.array() + kBrickSize - 1) / kBrickSize; }
};

// The probes per axis the default spacing aims for along the longest side of the scene.
constexpr int kDefaultProbesAlongLongestSide = 16;

// Cells of `spacing` covering `bounds`, one probe at each cell centre, the whole grid centred
// on the bounds: probes stay half a cell away from the outer walls of a closed room. An axis
// along which the scene is flat gets two probes, half a cell to either side of it.
// spacing <= 0 picks the default. An empty scene gets a single probe at the origin.
// Throws InputError if the grid would exceed `maxProbes`.
ProbeGrid makeProbeGrid(const Eigen::AlignedBox3f& bounds, double spacing, std::int64_t maxProbes);

}  // namespace baker
