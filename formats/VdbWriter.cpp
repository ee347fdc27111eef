#include "formats/VdbWriter.h"

#include <fmt/format.h>
#include <openvdb/io/Archive.h>
#include <openvdb/io/GridDescriptor.h>
#include <openvdb/io/io.h>
#include <openvdb/openvdb.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "formats/AtomicFile.h"
#include "formats/VdbChecksum.h"
#include "formats/VdbUuid.h"
#include "formats/VolumeHeader.h"
#include "formats/VolumeLayout.h"
#include "formats/VolumeMetadata.h"
#include "volume/PlacementSummary.h"
#include "volume/ProbeGrid.h"
#include "volume/StoredBricks.h"

namespace baker {
namespace {

// A stored brick (exactly one OpenVDB leaf) and, for each probe of it the level holds, the
// probe's voxel in the leaf and its row in the volume's arrays. Worked out once per level rather
// than once per grid: a volume has dozens of grids (84 for sh-l2 with a distance map).
struct StoredBrick {
  openvdb::Coord origin;
  std::vector<std::pair<openvdb::Index, std::int64_t>> voxelRows;
};

std::vector<StoredBrick> storedBrickVoxels(const Volume& v, const std::vector<bool>& stored) {
  static_assert(openvdb::FloatTree::LeafNodeType::DIM == kBrickSize, "a brick is one OpenVDB leaf");
  std::vector<StoredBrick> bricks;
  const ProbeGrid& g = v.grid;
  for (std::int64_t b = 0; b < g.brickCount(); ++b) {
    if (!stored[std::size_t(b)]) continue;
    const Eigen::Vector3i corner = g.brickCorner(b);
    StoredBrick& brick = bricks.emplace_back();
    brick.origin = openvdb::Coord(corner.x(), corner.y(), corner.z());
    // A sub-brick the level does not hold stays inactive at the background value, so that
    // OpenVDB's mask compression stores none of its voxels.
    forEachHeldProbeOfBrick(g, v.rows, b, [&](int i, int j, int k, std::int64_t row) {
      brick.voxelRows.emplace_back(openvdb::FloatTree::LeafNodeType::coordToOffset(openvdb::Coord(i, j, k)), row);
    });
  }
  return bricks;
}

// A grid holding the voxels of the stored bricks, every held one active (a constant value is data
// here, not background); `valueAt(row)`. A brick is filled in place as one leaf: going voxel by
// voxel through an accessor costs several times as much.
template <typename GridType, typename ValueAt>
typename GridType::Ptr sparseGrid(const std::vector<StoredBrick>& bricks, ValueAt valueAt) {
  using LeafType = typename GridType::TreeType::LeafNodeType;
  auto grid = GridType::create(typename GridType::ValueType(0));
  for (const StoredBrick& brick : bricks) {
    auto leaf = std::make_unique<LeafType>(brick.origin, typename GridType::ValueType(0), false);
    for (const auto& [voxel, row] : brick.voxelRows) leaf->setValueOn(voxel, valueAt(row));
    grid->tree().addLeaf(leaf.release());
  }
  return grid;
}

openvdb::Vec3i vec3i(const Eigen::Vector3i& v) { return {v.x(), v.y(), v.z()}; }
openvdb::Vec3d vec3d(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

openvdb::MetaMap fileMetadata(const Volume& v, const Basis& basis, bool hasProbeStates) {
  openvdb::MetaMap meta;
  for (const auto& [key, value] : describingMetadata(v, basis, hasProbeStates))
    meta.insertMeta(key, openvdb::StringMetadata(value));
  const ProbeGrid& g = v.grid;
  meta.insertMeta("baker.coefficients_per_probe", openvdb::Int32Metadata(v.coefficientsPerProbe));
  meta.insertMeta("baker.visibility_per_probe", openvdb::Int32Metadata(v.visibilityPerProbe));
  meta.insertMeta("baker.dims", openvdb::Vec3IMetadata(vec3i(g.dims)));
  meta.insertMeta("baker.origin", openvdb::Vec3DMetadata(vec3d(g.origin)));
  meta.insertMeta("baker.spacing", openvdb::DoubleMetadata(g.spacing));
  meta.insertMeta(kVdbChecksumKey, openvdb::StringMetadata(kVdbChecksumPlaceholder));
  return meta;
}

// Why the last file operation failed, as far as the C library says.
std::string failureReason() { return errno != 0 ? std::strerror(errno) : "the output stream failed"; }

// OpenVDB's public writer takes every grid at once, so all of a volume's grids (84 for sh-l2
// with a distance map, 102 with the sky's parts) would be alive together, each with its own 32³
// and 16³ internal nodes. Writing sixteen grids at a time bounds that; Archive's protected members write the same header
// and grid records as File::write, given what holds for our grids: none is null, their names are
// unique and not empty (so File::write would rename none), and none shares its tree with another
// (so none would be written as an instance).
//
// A grid's record does not depend on what precedes it but for three stream positions (where its
// data starts, where its buffers start, where it ends), so the grids of a batch are built and
// serialised side by side, each into its own buffer from position 0, and the positions are moved
// by where the record lands in the file. Most of a write is per grid (building the tree, its
// statistics, compressing its topology and buffers): this spreads it over the cores, and the file
// is the same bytes at any thread count.
class GridByGridArchive : public openvdb::io::Archive {
 public:
  // `gridAt(i)` builds grid i; it is called from several threads at once.
  template <typename GridAt>
  void writeGrids(std::ostream& os, const std::string& path, const openvdb::MetaMap& metadata, std::int32_t gridCount,
                  GridAt gridAt) const {
    auto streamMetadata = std::make_shared<openvdb::io::StreamMetadata>();
    openvdb::io::setStreamMetadataPtr(os, streamMetadata, /*transfer=*/false);
    openvdb::io::setDataCompression(os, compression());
    openvdb::io::setWriteGridStatsMetadata(os, isGridStatsMetadataEnabled());
    writeHeader(os, /*seekable=*/true);
    metadata.writeMeta(os);
    os.write(reinterpret_cast<const char*>(&gridCount), sizeof gridCount);
    std::vector<GridRecord> records;
    for (std::int32_t first = 0; first < gridCount; first += kGridsAtOnce) {
      records.clear();
      records.resize(std::size_t(std::min(kGridsAtOnce, gridCount - first)));
      tbb::parallel_for(0, int(records.size()),
                        [&](int k) { record(os, path, gridAt(first + k), &records[std::size_t(k)]); });
      for (GridRecord& r : records) {
        append(os, r);
        if (!os) throw std::runtime_error(fmt::format("{}: cannot write OpenVDB file: {}", path, failureReason()));
      }
    }
    openvdb::io::clearStreamMetadataPtr(os);
  }

 private:
  // Grids alive at once, whatever the cores: a bound on the memory the write adds to the volume's
  // (each grid holds one value of every probe), and enough to keep 8 cores busy.
  static constexpr std::int32_t kGridsAtOnce = 16;

  struct GridRecord {
    std::stringstream bytes{std::ios::in | std::ios::out | std::ios::binary};
    openvdb::io::GridDescriptor descriptor;
  };

  // The grid's record as writeGrid puts it in a stream with the file's settings (copied from
  // `file`: version, compression, statistics, stream metadata), starting at position 0.
  void record(const std::ostream& file, const std::string& path, const openvdb::GridBase::ConstPtr& grid,
              GridRecord* r) const {
    r->bytes.copyfmt(file);
    r->descriptor = openvdb::io::GridDescriptor(grid->getName(), grid->type(), grid->saveFloatAsHalf());
    writeGrid(r->descriptor, grid, r->bytes, /*seekable=*/true);
    if (!r->bytes) throw std::runtime_error(fmt::format("{}: cannot serialise grid '{}' in memory", path, grid->getName()));
  }

  // The record at the stream's position, its three positions (written by
  // GridDescriptor::writeStreamPos just before the grid's data) moved there.
  static void append(std::ostream& os, GridRecord& r) {
    const std::int64_t base = std::int64_t(os.tellp());
    const std::int64_t positions[3] = {r.descriptor.getGridPos() + base, r.descriptor.getBlockPos() + base,
                                       r.descriptor.getEndPos() + base};
    const std::int64_t at = r.descriptor.getGridPos() - std::int64_t(sizeof positions);
    if (at < 0 || r.descriptor.getEndPos() != std::int64_t(r.bytes.tellp()))
      throw std::logic_error("an OpenVDB grid record without its stream positions");
    r.bytes.seekp(at);
    r.bytes.write(reinterpret_cast<const char*>(positions), sizeof positions);
    r.bytes.seekg(0);
    os << r.bytes.rdbuf();
  }
};

// One level's grids: named `prefix` + the layout's name, with the level's own transform.
struct LevelGrids {
  const Volume* volume;
  std::string prefix;
  std::vector<bool> stored;
};

// A level's grid `spec`: its stored bricks' voxels.
openvdb::GridBase::Ptr levelGrid(const Volume& volume, const std::vector<StoredBrick>& bricks, const VolumeGrid& spec) {
  if (spec.kind == VolumeGrid::Kind::ProbeState)
    return sparseGrid<openvdb::Int32Grid>(bricks, [&](std::int64_t row) { return int(volume.states[std::size_t(row)]); });
  if (spec.kind == VolumeGrid::Kind::ProbeOffset)
    return sparseGrid<openvdb::Vec3SGrid>(bricks, [&](std::int64_t row) {
      const Eigen::Vector3f& offset = volume.offsets[std::size_t(row)];
      return openvdb::Vec3s(offset.x(), offset.y(), offset.z());
    });
  if (spec.components == 3) {
    const FloatColumn r = floatColumn(volume, spec, 0), g = floatColumn(volume, spec, 1), b = floatColumn(volume, spec, 2);
    return sparseGrid<openvdb::Vec3SGrid>(bricks, [&](std::int64_t row) { return openvdb::Vec3s(r[row], g[row], b[row]); });
  }
  const FloatColumn column = floatColumn(volume, spec, 0);
  return sparseGrid<openvdb::FloatGrid>(bricks, [&](std::int64_t row) { return column[row]; });
}

void writeLevels(const std::vector<LevelGrids>& levels, const Basis& basis, const openvdb::MetaMap& metadata,
                 bool hasProbeStates, const std::string& path) {
  for (const LevelGrids& level : levels) requireFiniteVolume(*level.volume);
  openvdb::initialize();
  const Volume& first = *levels.front().volume;
  const std::vector<VolumeGrid> specs =
      volumeGrids(basis, first.visibilityPerProbe, hasProbeStates, first.distanceMap,
                  distanceGridsWritten(first.distanceMap), first.keepsSkyDirect, first.keepsSkyBounced);
  std::vector<std::vector<StoredBrick>> bricks;
  for (const LevelGrids& level : levels) bricks.push_back(storedBrickVoxels(*level.volume, level.stored));
  const auto gridAt = [&](std::int32_t index) {
    const std::size_t n = std::size_t(index) / specs.size();
    const Volume& volume = *levels[n].volume;
    const VolumeGrid& spec = specs[std::size_t(index) % specs.size()];
    openvdb::GridBase::Ptr grid = levelGrid(volume, bricks[n], spec);
    grid->setName(levels[n].prefix + spec.name);
    openvdb::math::Transform::Ptr transform = openvdb::math::Transform::createLinearTransform(volume.grid.spacing);
    transform->postTranslate(vec3d(volume.grid.origin));
    grid->setTransform(transform);
    return grid;
  };

  AtomicFile out(path);
  try {
    errno = 0;
    std::ofstream file(out.temporaryPath(), std::ios::binary | std::ios::trunc);
    if (!file)
      throw std::runtime_error(fmt::format("{}: cannot create '{}': {}", path, out.temporaryPath(), failureReason()));
    GridByGridArchive().writeGrids(file, path, metadata, std::int32_t(specs.size() * levels.size()), gridAt);
    file.close();
    if (!file) throw std::runtime_error(fmt::format("{}: cannot write OpenVDB file: {}", path, failureReason()));
    deriveVdbUuid(out.temporaryPath());
    sealVdbChecksum(out.temporaryPath());
  } catch (const openvdb::Exception& e) {
    throw std::runtime_error(fmt::format("{}: cannot write OpenVDB file: {}", path, e.what()));
  }
  out.commit();
}

// The bricks a level holds: all of them are stored (the bake kept only those worth storing,
// volume/StoredBricks.h), so that a reader holds the same bricks, and samples the same levels, as
// the bake did.
std::vector<bool> heldBricks(const Volume& level) {
  std::vector<bool> held(std::size_t(level.grid.brickCount()));
  for (std::size_t b = 0; b < held.size(); ++b) held[b] = level.rows.holdsBrick(std::int64_t(b));
  return held;
}

}  // namespace

void writeVdb(const Volume& volume, const Basis& basis, const std::string& path) {
  const bool hasProbeStates = volume.hasProbeStates();
  writeLevels({{&volume, "", storedBricks(volume)}}, basis, fileMetadata(volume, basis, hasProbeStates), hasProbeStates,
              path);
}

void writeAdaptiveVdb(const AdaptiveVolume& volume, const Basis& basis, const std::string& path) {
  requireNoDistanceMap(volume);
  // Every level has probe states, though a shard's share may hold no probe of some level.
  openvdb::MetaMap metadata = fileMetadata(volume.coarsest(), basis, /*hasProbeStates=*/true);
  metadata.removeMeta("baker.format_version");
  metadata.insertMeta("baker.format_version", openvdb::StringMetadata(std::to_string(kLevelsFormatVersion)));
  metadata.insertMeta(kLevelsKey, openvdb::Int32Metadata(int(volume.levels.size())));
  metadata.insertMeta("baker.level_ratio", openvdb::Int32Metadata(kLevelRatio));
  metadata.insertMeta("baker.margin_cells", openvdb::Int32Metadata(volume.marginCells));
  if (volume.placement) {
    std::int64_t bricks = 0;
    for (const Volume& level : volume.levels) bricks += std::int64_t(heldBricksInOrder(level).size());
    metadata.removeMeta("baker.shard.bricks");
    metadata.insertMeta("baker.shard.bricks", openvdb::StringMetadata(std::to_string(bricks)));
    metadata.insertMeta(kPlacementKey, openvdb::StringMetadata(volume.placement->fingerprint));
    metadata.insertMeta(kPlacedBricksKey, openvdb::StringMetadata(bricksPerLevelText(volume.placement->bricksPerLevel)));
  }
  std::vector<LevelGrids> levels;
  for (std::size_t k = 0; k < volume.levels.size(); ++k) {
    const ProbeGrid& g = volume.levels[k].grid;
    if (k > 0) {
      const std::string key = fmt::format("baker.level{}.", k);
      metadata.insertMeta(key + "dims", openvdb::Vec3IMetadata(vec3i(g.dims)));
      metadata.insertMeta(key + "origin", openvdb::Vec3DMetadata(vec3d(g.origin)));
      metadata.insertMeta(key + "spacing", openvdb::DoubleMetadata(g.spacing));
    }
    levels.push_back({&volume.levels[k], levelGridPrefix(int(k)), heldBricks(volume.levels[k])});
  }
  writeLevels(levels, basis, metadata, /*hasProbeStates=*/true, path);
}

}  // namespace baker
