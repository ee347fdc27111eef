#include "formats/VdbReader.h"

#include <fmt/format.h>
#include <openvdb/openvdb.h>

#include <algorithm>
#include <cmath>

#include "basis/BasisRegistry.h"
#include "common/Error.h"
#include "formats/VdbChecksum.h"
#include "formats/VolumeHeader.h"
#include "formats/VolumeLayout.h"
#include "formats/VolumeMetadata.h"
#include "formats/LevelChecks.h"
#include "volume/LevelGrids.h"
#include "volume/SubBricks.h"

namespace baker {
namespace {

// Every metadata entry as text.
std::vector<std::pair<std::string, std::string>> textOf(const openvdb::MetaMap& meta) {
  std::vector<std::pair<std::string, std::string>> text;
  for (auto it = meta.beginMeta(); it != meta.endMeta(); ++it) text.push_back({it->first, it->second->str()});
  return text;
}

// What `f` makes of the file's metadata, the grids left unread.
template <typename F>
auto fromVdbMetadata(const std::string& path, F f) {
  openvdb::initialize();
  try {
    openvdb::io::File file(path);
    file.open(false);
    auto result = f(*file.getMetadata());
    file.close();
    return result;
  } catch (const openvdb::Exception& e) {
    throw InputError(fmt::format("{}: not a readable OpenVDB volume: {}", path, e.what()));
  }
}

template <typename T>
T required(const openvdb::MetaMap& meta, const std::string& key, const std::string& path) {
  auto value = meta.getMetadata<openvdb::TypedMetadata<T>>(key);
  if (!value) throw InputError(fmt::format("{}: metadata '{}' is missing or has the wrong type", path, key));
  return value->value();
}

ProbeGrid levelGrid(const openvdb::MetaMap& meta, const std::string& key, const std::string& path) {
  const openvdb::Vec3i dims = required<openvdb::Vec3i>(meta, key + "dims", path);
  const openvdb::Vec3d origin = required<openvdb::Vec3d>(meta, key + "origin", path);
  ProbeGrid grid;
  grid.dims = Eigen::Vector3i(dims.x(), dims.y(), dims.z());
  grid.origin = Eigen::Vector3d(origin.x(), origin.y(), origin.z());
  grid.spacing = required<double>(meta, key + "spacing", path);
  return grid;
}

// Grid `name` of the file as a GridType; InputError when it is missing or of another type.
template <typename GridType>
typename GridType::Ptr requiredGrid(openvdb::io::File& file, const std::string& name, const std::string& path) {
  if (!file.hasGrid(name)) throw InputError(fmt::format("{}: grid '{}' is missing", path, name));
  auto grid = openvdb::gridPtrCast<GridType>(file.readGrid(name));
  if (!grid) throw InputError(fmt::format("{}: grid '{}' has the wrong value type", path, name));
  return grid;
}

// A voxel outside the bricks the volume holds: another shard's (a part read as its own bricks
// only), or a brick a level does not hold (no leaf in its probe_state grid).
InputError voxelNotHeld(const std::string& path, const std::string& name, const Volume& v, std::int64_t p) {
  if (v.shard)
    return InputError(fmt::format("{}: grid '{}' holds probe {}, outside the bricks of its shard {}", path, name, p,
                                  shardName(*v.shard)));
  return InputError(fmt::format("{}: grid '{}' holds probe {}, in a brick or sub-brick its level's probe_state grid "
                                "does not hold", path, name, p));
}

// Copies the active voxels of one grid into the volume, refusing voxels outside the grid.
template <typename GridType, typename Store>
void readVoxels(openvdb::io::File& file, const std::string& name, const ProbeGrid& g, const std::string& path,
                Store store) {
  const auto grid = requiredGrid<GridType>(file, name, path);
  for (auto it = grid->cbeginValueOn(); it; ++it) {
    const openvdb::Coord c = it.getCoord();
    if (c.x() < 0 || c.y() < 0 || c.z() < 0 || c.x() >= g.dims.x() || c.y() >= g.dims.y() || c.z() >= g.dims.z())
      throw InputError(fmt::format("{}: grid '{}' has a voxel at ({}, {}, {}), outside the {} × {} × {} probes", path,
                                   name, c.x(), c.y(), c.z(), g.dims.x(), g.dims.y(), g.dims.z()));
    store(g.linearIndex(c.x(), c.y(), c.z()), *it);
  }
}

// The distance atlas's voxels into the maps of the probes they belong to, refusing a voxel
// outside the atlas of the grid's probes or of a probe the volume does not hold.
void readDistanceAtlas(openvdb::io::File& file, const std::string& name, const std::string& path, Volume& volume) {
  const auto grid = requiredGrid<openvdb::Vec3SGrid>(file, name, path);
  const ProbeGrid& g = volume.grid;
  const int size = volume.distanceMap.size;
  const std::vector<VolumeGrid> texelGrids = perProbeGridsOf({name, VolumeGrid::Kind::DistanceAtlas, 3}, volume.distanceMap);
  for (auto it = grid->cbeginValueOn(); it; ++it) {
    const openvdb::Coord c = it.getCoord();
    Eigen::Vector3i probe;
    int t = 0;
    if (!probeOfAtlasVoxel({c.x(), c.y(), c.z()}, size, g.dims, probe, t))
      throw InputError(fmt::format("{}: grid '{}' has a voxel at ({}, {}, {}), outside the atlas of {} × {} × {} probes' "
                                   "maps of {} × {} texels", path, name, c.x(), c.y(), c.z(), g.dims.x(), g.dims.y(),
                                   g.dims.z(), size, size));
    const std::int64_t p = g.linearIndex(probe.x(), probe.y(), probe.z());
    for (int component = 0; component < 3; ++component)
      if (!setGridValue(volume, texelGrids[std::size_t(t)], component, p, (*it)[component]))
        throw voxelNotHeld(path, name, volume, p);
  }
}

// The grids of one level (named `prefix` + the layout's name) into `volume`, sized already.
void readLevelGrids(openvdb::io::File& file, const std::string& path, const std::string& prefix,
                    const VolumeHeader& header, Volume& volume) {
  const std::unique_ptr<Basis> basis = makeBasis(volume.basisName);
  const ProbeGrid& g = volume.grid;
  for (const VolumeGrid& spec : volumeGrids(*basis, volume.visibilityPerProbe, header.hasProbeStates,
                                            volume.distanceMap, distanceGridsInFile(header.text),
                                            volume.keepsSkyDirect, volume.keepsSkyBounced)) {
    const std::string name = prefix + spec.name;
    if (spec.kind == VolumeGrid::Kind::DistanceAtlas)
      readDistanceAtlas(file, name, path, volume);
    else if (spec.kind == VolumeGrid::Kind::ProbeState)
      readVoxels<openvdb::Int32Grid>(file, name, g, path, [&](std::int64_t p, int state) {
        if (state < 0 || state >= kProbeStateCount)
          throw InputError(fmt::format("{}: grid '{}' holds {}; states are 0, 1, 2 or 3", path, name, state));
        const std::int64_t row = volume.rowOf(p);
        if (row < 0) throw voxelNotHeld(path, name, volume, p);
        volume.states[row] = ProbeState(state);
      });
    else if (spec.components == 3)
      readVoxels<openvdb::Vec3SGrid>(file, name, g, path, [&](std::int64_t p, const openvdb::Vec3s& v) {
        for (int c = 0; c < 3; ++c)
          if (!setGridValue(volume, spec, c, p, v[c])) throw voxelNotHeld(path, name, volume, p);
      });
    else
      readVoxels<openvdb::FloatGrid>(file, name, g, path, [&](std::int64_t p, float v) {
        if (!setGridValue(volume, spec, 0, p, v)) throw voxelNotHeld(path, name, volume, p);
      });
  }
}

// The header every level shares: basis, counts, level 0's grid and the text metadata.
VolumeHeader vdbHeader(openvdb::io::File& file, const openvdb::MetaMap& meta, const std::string& path) {
  VolumeHeader header;
  header.basisName = required<std::string>(meta, "baker.basis", path);
  header.coefficientsPerProbe = required<int>(meta, "baker.coefficients_per_probe", path);
  auto visibility = meta.getMetadata<openvdb::Int32Metadata>("baker.visibility_per_probe");
  header.visibilityPerProbe = visibility ? visibility->value() : 0;
  header.grid = levelGrid(meta, "baker.", path);
  header.hasProbeStates = file.hasGrid("probe_state");
  header.text = textOf(meta);
  return header;
}

// Levels the file holds: 1 without the key.
int levelCount(const openvdb::MetaMap& meta, const std::string& path) {
  if (!meta[kLevelsKey]) return 1;
  const int levels = required<int>(meta, kLevelsKey, path);
  if (levels < 1 || levels > kMaxLevels)
    throw InputError(fmt::format("{}: {} is {}; a volume has 1 to {} levels", path, kLevelsKey, levels, kMaxLevels));
  return levels;
}

// The sub-bricks of a probe_state leaf with an active voxel; InputError unless each of them has
// every voxel inside the grid active (a sub-brick is held whole or not at all).
std::uint8_t subBricksActive(const openvdb::Int32Grid::TreeType::LeafNodeType& leaf, const ProbeGrid& g,
                             const std::string& name, const std::string& path) {
  const openvdb::Coord o = leaf.origin();
  const std::int64_t brick = g.brickOf(o.x(), o.y(), o.z());
  std::uint8_t active = 0;
  for (auto voxel = leaf.cbeginValueOn(); voxel; ++voxel) {
    const openvdb::Coord c = voxel.getCoord();
    active = std::uint8_t(active | subBrickBit(c.x(), c.y(), c.z()));
  }
  const Eigen::Vector3i lo(o.x(), o.y(), o.z()), hi = lo + g.brickExtent(brick);
  for (int k = lo.z(); k < hi.z(); ++k)
    for (int j = lo.y(); j < hi.y(); ++j)
      for (int i = lo.x(); i < hi.x(); ++i)
        if ((active & subBrickBit(i, j, k)) && !leaf.isValueOn(openvdb::Coord(i, j, k)))
          throw InputError(fmt::format("{}: grid '{}' holds part of the sub-brick of probe ({}, {}, {}); a level holds "
                                       "sub-bricks of 4³ whole", path, name, i, j, k));
  return active;
}

// The bricks of a level's grid that hold a leaf of its probe_state grid, by increasing index,
// and the sub-bricks each holds (its active voxels).
std::vector<std::int64_t> bricksInFile(openvdb::io::File& file, const std::string& name, const ProbeGrid& g,
                                       const std::string& path, std::vector<std::uint8_t>& masks) {
  const auto grid = requiredGrid<openvdb::Int32Grid>(file, name, path);
  std::vector<std::int64_t> bricks;
  for (auto leaf = grid->tree().cbeginLeaf(); leaf; ++leaf) {
    const openvdb::Coord c = leaf->origin();
    if (c.x() < 0 || c.y() < 0 || c.z() < 0 || c.x() >= g.dims.x() || c.y() >= g.dims.y() || c.z() >= g.dims.z())
      throw InputError(fmt::format("{}: grid '{}' has a brick at ({}, {}, {}), outside the {} × {} × {} probes", path,
                                   name, c.x(), c.y(), c.z(), g.dims.x(), g.dims.y(), g.dims.z()));
    bricks.push_back(g.brickOf(c.x(), c.y(), c.z()));
    masks.push_back(subBricksActive(*leaf, g, name, path));
  }
  // OpenVDB visits leaves in its tree's order, not by brick index.
  std::vector<std::size_t> order(bricks.size());
  for (std::size_t n = 0; n < order.size(); ++n) order[n] = n;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return bricks[a] < bricks[b]; });
  std::vector<std::int64_t> sortedBricks;
  std::vector<std::uint8_t> sortedMasks;
  for (const std::size_t n : order) {
    sortedBricks.push_back(bricks[n]);
    sortedMasks.push_back(masks[n]);
  }
  masks = std::move(sortedMasks);
  return sortedBricks;
}

// A uniform volume from its open file.
Volume readUniform(openvdb::io::File& file, const openvdb::MetaMap& meta, const std::string& path, PartReading parts) {
  if (meta[kPlacementKey])
    throw InputError(fmt::format("{}: {} on a volume of one level; a part of an adaptive bake has 2 or more "
                                 "(baker.levels): the file is damaged",
                                 path, kPlacementKey));
  const VolumeHeader header = vdbHeader(file, meta, path);
  Volume volume = header.emptyVolume(path, parts);
  readLevelGrids(file, path, "", header, volume);
  requireFiniteValues(volume, path);
  return volume;
}

// The whole bake's placement a shard's part of an adaptive bake records.
PlacementSummary placementOf(const openvdb::MetaMap& meta, int levels, const std::string& path) {
  PlacementSummary placement;
  placement.fingerprint = required<std::string>(meta, kPlacementKey, path);
  const std::string counts = required<std::string>(meta, kPlacedBricksKey, path);
  if (!parseBricksPerLevel(counts, placement.bricksPerLevel) || int(placement.bricksPerLevel.size()) != levels)
    throw InputError(fmt::format("{}: {} \"{}\" is not {} brick counts separated by commas", path, kPlacedBricksKey,
                                 counts, levels));
  return placement;
}

// Every level of an adaptive volume from its open file; the probes held in all levels together
// are checked against the limit and this machine's memory before each level is allocated.
AdaptiveVolume readLevelsOf(openvdb::io::File& file, const openvdb::MetaMap& meta, int levels, const std::string& path) {
  AdaptiveVolume volume;
  volume.marginCells = required<int>(meta, "baker.margin_cells", path);
  if (required<int>(meta, "baker.level_ratio", path) != kLevelRatio)
    throw InputError(fmt::format("{}: baker.level_ratio is not {}, the only ratio this reader knows", path, kLevelRatio));
  VolumeHeader header = vdbHeader(file, meta, path);
  if (!header.hasProbeStates) throw InputError(fmt::format("{}: grid 'probe_state' is missing", path));
  const std::unique_ptr<Basis> basis = makeBasis(header.basisName);
  LevelChecks checks(*basis, path);
  checks.margin(volume.marginCells, "baker.margin_cells");
  for (int level = 0; level < levels; ++level) {
    const std::string key = level == 0 ? "baker." : fmt::format("baker.level{}.", level);
    if (level > 0) header.grid = levelGrid(meta, key, path);
    checks.grid(level, header.grid, key);
    std::vector<std::uint8_t> masks;
    header.heldBricks = bricksInFile(file, levelGridPrefix(level) + "probe_state", header.grid, path, masks);
    header.heldMasks = std::move(masks);
    checks.held(level, header.heldBricks->size());
    volume.levels.push_back(header.emptyVolume(path));
    if (level > 0) {
      volume.levels.back().settings.clear();
      volume.levels.back().sky.reset();
    }
    readLevelGrids(file, path, levelGridPrefix(level), header, volume.levels.back());
    requireFiniteValues(volume.levels.back(), path);
  }
  if (volume.coarsest().shard) volume.placement = placementOf(meta, levels, path);
  return volume;
}

// Opens the file after checking its checksum and gives it, its metadata and its level count to `read`.
template <typename Read>
auto withVdb(const std::string& path, Read read) {
  requireVdbChecksum(path);
  openvdb::initialize();
  try {
    openvdb::io::File file(path);
    file.open();
    openvdb::MetaMap::Ptr meta = file.getMetadata();
    auto result = read(file, *meta, levelCount(*meta, path));
    file.close();
    return result;
  } catch (const openvdb::Exception& e) {
    throw InputError(fmt::format("{}: not a readable OpenVDB volume: {}", path, e.what()));
  }
}

}  // namespace

Volume readVdb(const std::string& path, PartReading parts) {
  return withVdb(path, [&](openvdb::io::File& file, const openvdb::MetaMap& meta, int levels) {
    if (levels > 1)
      throw InputError(fmt::format("{}: an adaptive volume of {} levels; this command reads a uniform volume only "
                                   "(docs/ADAPTIVE.md says which commands read levels)",
                                   path, levels));
    return readUniform(file, meta, path, parts);
  });
}

AdaptiveVolume readAdaptiveVdb(const std::string& path) {
  return withVdb(path, [&](openvdb::io::File& file, const openvdb::MetaMap& meta, int levels) {
    if (levels > 1) return readLevelsOf(file, meta, levels, path);
    AdaptiveVolume volume;
    volume.levels.push_back(readUniform(file, meta, path, PartReading::EveryProbe));
    return volume;
  });
}

int vdbLevelCount(const std::string& path) {
  return fromVdbMetadata(path, [&](const openvdb::MetaMap& meta) { return levelCount(meta, path); });
}

std::vector<std::pair<std::string, std::string>> vdbMetadataText(const std::string& path) {
  return fromVdbMetadata(path, [](const openvdb::MetaMap& meta) { return textOf(meta); });
}

}  // namespace baker
