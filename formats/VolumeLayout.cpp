#include "formats/VolumeLayout.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "volume/ProbeGrid.h"
#include "volume/StoredBricks.h"

namespace baker {

namespace {

void addCoefficientGrids(const Basis& basis, VolumeGrid::Kind kind, const std::string& prefix,
                         std::vector<VolumeGrid>& grids) {
  if (basis.channelsShareFunctions()) {
    for (int f = 0; f < basis.coefficientCount(0); ++f)
      grids.push_back({fmt::format("{}rgb_{:02}", prefix, f), kind, 3,
                       {basis.coefficientOffset(0) + f, basis.coefficientOffset(1) + f, basis.coefficientOffset(2) + f}});
  } else {
    for (int c = 0; c < 3; ++c)
      for (int f = 0; f < basis.coefficientCount(c); ++f)
        grids.push_back({fmt::format("{}{}_{:02}", prefix, channelName(basis.colorSpace(), c), f), kind, 1,
                         {basis.coefficientOffset(c) + f, 0, 0}});
  }
}

}  // namespace

DistanceGrids distanceGridsWritten(const DistanceMapLayout& layout, VolumeFile file) {
  if (!layout.skyVisibility) return DistanceGrids::ScalarPerValue;
  return file == VolumeFile::OpenVdb ? DistanceGrids::Atlas : DistanceGrids::RgbPerTexel;
}

VolumeGrid distanceTexelGrid(int t, int texels) {
  return {fmt::format("distance_map_{:03}", t), VolumeGrid::Kind::DistanceMap, 3, {2 * t, 2 * t + 1, 2 * texels + t}};
}

std::vector<VolumeGrid> perProbeGridsOf(const VolumeGrid& grid, const DistanceMapLayout& map) {
  if (grid.kind != VolumeGrid::Kind::DistanceAtlas) return {grid};
  std::vector<VolumeGrid> texelGrids;
  for (int t = 0; t < map.texels(); ++t) texelGrids.push_back(distanceTexelGrid(t, map.texels()));
  return texelGrids;
}

bool probeOfAtlasVoxel(const AtlasVoxel& voxel, int size, const Eigen::Vector3i& dims, Eigen::Vector3i& probe, int& t) {
  if (voxel.x < 0 || voxel.y < 0 || voxel.z < 0 || voxel.x >= std::int64_t(dims.x()) * size ||
      voxel.y >= std::int64_t(dims.y()) * size || voxel.z >= dims.z())
    return false;
  probe = Eigen::Vector3i(int(voxel.x / size), int(voxel.y / size), int(voxel.z));
  t = int(voxel.x % size) + size * int(voxel.y % size);
  return true;
}

std::vector<VolumeGrid> volumeGrids(const Basis& basis, int visibilityPerProbe, bool hasProbeStates,
                                    const DistanceMapLayout& distanceMap, DistanceGrids distanceGrids, bool skyDirect,
                                    bool skyBounced) {
  std::vector<VolumeGrid> grids;
  addCoefficientGrids(basis, VolumeGrid::Kind::Coefficients, "", grids);
  if (skyDirect) addCoefficientGrids(basis, VolumeGrid::Kind::SkyDirect, "sky_direct_", grids);
  if (skyBounced) addCoefficientGrids(basis, VolumeGrid::Kind::SkyBounced, "sky_bounced_", grids);
  for (int f = 0; f < visibilityPerProbe; ++f)
    grids.push_back({fmt::format("visibility_{:02}", f), VolumeGrid::Kind::Visibility, 1, {f, 0, 0}});
  const int texels = distanceMap.size > 0 ? distanceMap.texels() : 0, moments = 2 * texels;
  if (texels > 0 && distanceMap.skyVisibility && distanceGrids == DistanceGrids::Atlas) {
    grids.push_back({"distance_map", VolumeGrid::Kind::DistanceAtlas, 3, {0, 0, 0}});
  } else if (texels > 0 && distanceMap.skyVisibility && distanceGrids == DistanceGrids::RgbPerTexel) {
    for (int t = 0; t < texels; ++t) grids.push_back(distanceTexelGrid(t, texels));
  } else {
    for (int f = 0; f < moments; ++f)
      grids.push_back({fmt::format("distance_moments_{:03}", f), VolumeGrid::Kind::DistanceMoments, 1, {f, 0, 0}});
    if (texels > 0 && distanceMap.skyVisibility)
      for (int t = 0; t < texels; ++t)
        grids.push_back({fmt::format("sky_visibility_map_{:03}", t), VolumeGrid::Kind::SkyVisibilityMap, 1, {moments + t, 0, 0}});
  }
  if (hasProbeStates) {
    grids.push_back({"probe_state", VolumeGrid::Kind::ProbeState, 1, {0, 0, 0}});
    grids.push_back({"probe_offset", VolumeGrid::Kind::ProbeOffset, 3, {0, 1, 2}});
  }
  return grids;
}

std::vector<VolumeGrid> volumeGrids(const Basis& basis, const Volume& volume, VolumeFile file) {
  return volumeGrids(basis, volume.visibilityPerProbe, volume.hasProbeStates(), volume.distanceMap,
                     distanceGridsWritten(volume.distanceMap, file),
                     volume.keepsSkyDirect, volume.keepsSkyBounced);
}

std::string componentName(const VolumeGrid& grid, int component) {
  if (grid.components == 1) return grid.name;
  static const char* rgb[3] = {"R", "G", "B"};
  static const char* xyz[3] = {"X", "Y", "Z"};
  return grid.name + "." + (grid.kind == VolumeGrid::Kind::ProbeOffset ? xyz : rgb)[component];
}

float gridValue(const Volume& v, const VolumeGrid& grid, int component, std::int64_t probe) {
  const std::int64_t row = v.rowOf(probe);
  if (row < 0) return grid.kind == VolumeGrid::Kind::ProbeState ? float(ProbeState::Invalid) : 0.0f;
  if (grid.kind == VolumeGrid::Kind::ProbeState) return float(v.states[std::size_t(row)]);
  if (grid.kind == VolumeGrid::Kind::ProbeOffset) return v.offsets[std::size_t(row)][component];
  return floatColumn(v, grid, component)[row];
}

FloatColumn floatColumn(const Volume& v, const VolumeGrid& grid, int component) {
  // A volume that holds no probe (a shard's empty part, a level without bricks) has empty arrays,
  // whose data() may be null: no offset is applied to it, and no row is read.
  const auto column = [&](const std::vector<float>& values, int stride) -> FloatColumn {
    return {values.empty() ? nullptr : values.data() + grid.index[component], stride};
  };
  switch (grid.kind) {
    case VolumeGrid::Kind::Coefficients: return column(v.coefficients, v.coefficientsPerProbe);
    case VolumeGrid::Kind::SkyDirect: return column(v.skyDirect, v.coefficientsPerProbe);
    case VolumeGrid::Kind::SkyBounced: return column(v.skyBounced, v.coefficientsPerProbe);
    case VolumeGrid::Kind::Visibility: return column(v.visibility, v.visibilityPerProbe);
    case VolumeGrid::Kind::DistanceMap:
    case VolumeGrid::Kind::DistanceMoments:
    case VolumeGrid::Kind::SkyVisibilityMap: return column(v.distanceMoments, v.distanceMomentsPerProbe());
    case VolumeGrid::Kind::DistanceAtlas:
    case VolumeGrid::Kind::ProbeState:
    case VolumeGrid::Kind::ProbeOffset: break;
  }
  throw std::logic_error(fmt::format("grid '{}' is not held as floats row by row", grid.name));
}

bool setGridValue(Volume& v, const VolumeGrid& grid, int component, std::int64_t probe, float value) {
  const std::int64_t row = v.rowOf(probe);
  if (row < 0) return false;
  switch (grid.kind) {
    case VolumeGrid::Kind::Coefficients: v.coefficients[row * v.coefficientsPerProbe + grid.index[component]] = value; break;
    case VolumeGrid::Kind::SkyDirect: v.skyDirect[row * v.coefficientsPerProbe + grid.index[component]] = value; break;
    case VolumeGrid::Kind::SkyBounced: v.skyBounced[row * v.coefficientsPerProbe + grid.index[component]] = value; break;
    case VolumeGrid::Kind::Visibility: v.visibility[row * v.visibilityPerProbe + grid.index[component]] = value; break;
    case VolumeGrid::Kind::DistanceMap:
    case VolumeGrid::Kind::DistanceMoments:
    case VolumeGrid::Kind::SkyVisibilityMap:
      v.distanceMoments[row * v.distanceMomentsPerProbe() + grid.index[component]] = value;
      break;
    case VolumeGrid::Kind::ProbeState: v.states[row] = ProbeState(std::uint8_t(value)); break;
    case VolumeGrid::Kind::ProbeOffset: v.offsets[row][component] = value; break;
    case VolumeGrid::Kind::DistanceAtlas:
      throw std::logic_error("the distance atlas holds many values a probe: it is set texel by texel");
  }
  return true;
}

void prepareForReading(Volume& v, bool hasProbeStates) {
  const std::size_t n = std::size_t(v.rows.count(v.grid));
  for (const auto& [values, width] : v.floatRows()) values->assign(n * std::size_t(width), 0.0f);
  v.states.assign(hasProbeStates ? n : 0, ProbeState::Invalid);
  v.offsets.assign(hasProbeStates ? n : 0, Eigen::Vector3f::Zero());
}

std::vector<bool> storedBricks(const Volume& v) {
  return v.shard ? bricksWithAProbeOutsideGeometry(v) : bricksWorthStoring(v);
}

void requireNoDistanceMap(const AdaptiveVolume& volume) {
  for (const Volume& level : volume.levels)
    if (level.distanceMomentsPerProbe() > 0)
      throw std::logic_error("a volume with levels holds a distance map, which its format has no grids for");
}

void requireFiniteVolume(const Volume& v) {
  for (const auto& [values, perProbe] : v.floatRows()) {
    // One pass without an early exit, which the compiler vectorises; the culprit is looked for
    // only when there is one.
    bool finite = true;
    for (const float value : *values) finite &= std::isfinite(value);
    if (finite) continue;
    const auto bad = std::find_if(values->begin(), values->end(), [](float value) { return !std::isfinite(value); });
    const std::size_t i = std::size_t(bad - values->begin());
    throw std::runtime_error(fmt::format("internal error: probe {} has a non-finite value; nothing written",
                                         v.rows.probeAt(v.grid, std::int64_t(i / std::max<std::size_t>(1, perProbe)))));
  }
}

}  // namespace baker
