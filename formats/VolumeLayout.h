#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "basis/Basis.h"
#include "volume/AdaptiveVolume.h"
#include "volume/Volume.h"

namespace baker {

// Every value a volume stores per probe, as named grids, the same for every file format:
//  - coefficients: when R, G and B share their functions, function NN of all three channels is
//    one RGB grid "rgb_NN"; otherwise each channel's function NN is a scalar grid named after
//    the channel, e.g. "Y_NN", "Co_NN", "Cg_NN";
//  - the directly seen sky's part of the coefficients (Volume::skyDirect), when the volume keeps
//    it: the same grids prefixed "sky_direct_", e.g. "sky_direct_rgb_NN"; the sky's part off
//    surfaces (Volume::skyBounced) likewise, prefixed "sky_bounced_";
//  - sky visibility, function NN of channel 0's set: a scalar grid "visibility_NN";
//  - the probe's distance map (volume/DistanceMoments.h), as DistanceGrids says;
//  - "probe_state" (0 inside geometry and filled from neighbours, 1 valid, 2 moved out of
//    geometry) and "probe_offset" (world-space move from the grid position, three components).
struct VolumeGrid {
  // DistanceMap, DistanceMoments and SkyVisibilityMap index the probe's distance-map values;
  // DistanceAtlas holds all of them, size² voxels a probe (distanceAtlasVoxel).
  enum class Kind {
    Coefficients,
    SkyDirect,
    SkyBounced,
    Visibility,
    DistanceAtlas,
    DistanceMap,
    DistanceMoments,
    SkyVisibilityMap,
    ProbeState,
    ProbeOffset
  };
  std::string name;
  Kind kind = Kind::Coefficients;
  int components = 1;  // 1 or 3
  // Where component c lives in the probe's coefficients (Coefficients, SkyDirect, SkyBounced), visibility values
  // (Visibility) or distance moments (DistanceMoments); unused for the probe grids.
  int index[3] = {0, 0, 0};
};

// How a file holds each probe's distance map:
//  - Atlas, how a .vdb holds a map with the sky's share (format 7): one RGB grid "distance_map" of
//    size² voxels a probe, texel t = u + size·v of probe (i, j, k) at voxel (i·size + u, j·size + v,
//    k) (distanceAtlasVoxel), R its mean distance, G its mean squared distance, B its escaped share
//    (each grid costs OpenVDB a fixed amount of work and bytes, whatever it holds);
//  - RgbPerTexel, how EXR slices hold one (and .vdb files of format 6): texel NNN's R, G and B as
//    one grid "distance_map_NNN", a channel set of each slice;
//  - ScalarPerValue, files before format 6 and maps without the sky's share: value NNN of the
//    probe's map as a scalar grid "distance_moments_NNN", the escaped shares as
//    "sky_visibility_map_NNN".
enum class DistanceGrids { Atlas, RgbPerTexel, ScalarPerValue };
// The kinds of file a volume is written to, whose grids differ only in the distance map's form.
enum class VolumeFile { OpenVdb, ExrSlices };
// The form a map of `layout` is written in now, to a file of kind `file`.
DistanceGrids distanceGridsWritten(const DistanceMapLayout& layout, VolumeFile file);

// `distanceGrids`: the form of the file read, or distanceGridsWritten for one being written.
std::vector<VolumeGrid> volumeGrids(const Basis& basis, int visibilityPerProbe, bool hasProbeStates,
                                    const DistanceMapLayout& distanceMap, DistanceGrids distanceGrids, bool skyDirect,
                                    bool skyBounced);
// The grids `volume` is written with to a file of kind `file` (its probe states as
// Volume::hasProbeStates says).
std::vector<VolumeGrid> volumeGrids(const Basis& basis, const Volume& volume, VolumeFile file);

// Texel t's RGB grid of a map of `texels` texels a probe (DistanceGrids::RgbPerTexel): where its
// mean distance, mean squared distance and escaped share sit in the probe's distance moments.
// The atlas holds the same three values at each of its voxels.
VolumeGrid distanceTexelGrid(int t, int texels);
// Where texel t = u + size·v of probe (i, j, k) lies in the atlas, and back (false for a voxel
// outside the `dims` probes).
struct AtlasVoxel {
  std::int64_t x, y, z;
};
inline AtlasVoxel distanceAtlasVoxel(int i, int j, int k, int u, int v, int size) {
  return {std::int64_t(i) * size + u, std::int64_t(j) * size + v, k};
}
// The grids whose values `grid` holds, each with one value a probe: the atlas holds every texel
// grid of `map`, any other grid its own.
std::vector<VolumeGrid> perProbeGridsOf(const VolumeGrid& grid, const DistanceMapLayout& map);
bool probeOfAtlasVoxel(const AtlasVoxel& voxel, int size, const Eigen::Vector3i& dims, Eigen::Vector3i& probe, int& t);

// Names of a grid's components where a format stores them one by one (EXR channels):
// "rgb_00.R", "probe_offset.X", or the grid's own name for a scalar grid.
std::string componentName(const VolumeGrid& grid, int component);

// Zero (an Invalid state) for a probe the volume does not hold; std::logic_error for the atlas,
// which holds many values a probe.
float gridValue(const Volume& volume, const VolumeGrid& grid, int component, std::int64_t probe);

// Where a component of a grid held as floats (not ProbeState or ProbeOffset) sits in a volume's
// arrays: row r's value is at values[r * stride]. What a writer reads probe after probe, rather
// than going through the kind of grid at each value.
struct FloatColumn {
  const float* values = nullptr;
  std::int64_t stride = 0;
  float operator[](std::int64_t row) const { return values[row * stride]; }
};
// std::logic_error for ProbeState, ProbeOffset and DistanceAtlas.
FloatColumn floatColumn(const Volume& volume, const VolumeGrid& grid, int component);
// Sizes `volume`'s arrays are expected to have already (see prepareForReading). False, storing
// nothing, for a probe the volume does not hold (a part read as its own bricks only).
// std::logic_error for DistanceAtlas.
[[nodiscard]] bool setGridValue(Volume& volume, const VolumeGrid& grid, int component, std::int64_t probe, float value);

// Sizes a volume's arrays for the probes it holds (Volume::rows) before a reader fills them:
// zeros, probes Invalid (what a sparse file's missing bricks mean) when the file has probe states.
void prepareForReading(Volume& volume, bool hasProbeStates);

// Bricks of 8³ probes (OpenVDB leaves) that sparse formats store (the others read as zeros, state
// Invalid): a whole volume's bricksWorthStoring; a shard's part, whose neighbours are not baked
// yet, keeps the bricks holding a probe that is not Invalid.
std::vector<bool> storedBricks(const Volume& volume);

// Writers refuse to store a NaN or an infinity (std::runtime_error: it would be a bug upstream).
void requireFiniteVolume(const Volume& volume);
// Writers of levels (format 5) refuse a level with a distance map (std::logic_error): that format
// names no grid for one, and a reader of it would miss the map. Bakes with levels make none.
void requireNoDistanceMap(const AdaptiveVolume& volume);

}  // namespace baker
