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
// than once per grid: a volume has dozens of grids (39 for sh-l2 with the sky's parts).
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
  for (const auto& [key, value] : describingMetadata(v, basis, hasProbeStates, VolumeFile::OpenVdb))
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

// What a writer of grids builds: a grid, and whether it is serialised straight into the file in
// its turn rather than beside the others into a buffer of its own.
struct BuiltGrid {
  openvdb::GridBase::Ptr grid;
  bool direct = false;
};

// OpenVDB's public writer takes every grid at once, so all of a volume's grids (21 for sh-l2
// with a distance map, 39 with the sky's parts) would be alive together, each with its own 32³
// and 16³ internal nodes. Writing sixteen grids at a time bounds that; Archive's protected members
// write the same header and grid records as File::write, given what holds for our grids: none is
// null, their names are unique and not empty (so File::write would rename none), and none shares
// its tree with another (so none would be written as an instance). One difference: a record
// carries no `file_delayed_load` metadata (see writeRecord).
//
// A grid's record does not depend on what precedes it but for three stream positions (where its
// data starts, where its buffers start, where it ends), so the grids of a batch are built and
// serialised side by side, each into its own buffer from position 0, and the positions are moved
// by where the record lands in the file. Most of a write is per grid (building the tree, its
// statistics, compressing its topology and buffers): this spreads it over the cores, and the file
// is the same bytes at any thread count.
class GridByGridArchive : public openvdb::io::Archive {
 public:
  // `gridAt(i)` builds grid i (a BuiltGrid); it is called from several threads at once. Returns
  // the bytes of the file's header and metadata, which hold the checksum's placeholder.
  template <typename GridAt>
  std::uint64_t writeGrids(std::ostream& os, const std::string& path, const openvdb::MetaMap& metadata,
                           std::int32_t gridCount, GridAt gridAt) const {
    // OpenVDB keeps in the stream the address of this pointer, not the pointer.
    auto streamMetadata = std::make_shared<openvdb::io::StreamMetadata>();
    openvdb::io::setStreamMetadataPtr(os, streamMetadata, /*transfer=*/false);
    openvdb::io::setDataCompression(os, compression());
    openvdb::io::setWriteGridStatsMetadata(os, isGridStatsMetadataEnabled());
    writeHeader(os, /*seekable=*/true);
    metadata.writeMeta(os);
    const std::uint64_t headerBytes = std::uint64_t(os.tellp());
    os.write(reinterpret_cast<const char*>(&gridCount), sizeof gridCount);
    std::vector<GridRecord> records;
    for (std::int32_t first = 0; first < gridCount; first += kGridsAtOnce) {
      records.clear();
      records.resize(std::size_t(std::min(kGridsAtOnce, gridCount - first)));
      tbb::parallel_for(0, int(records.size()),
                        [&](int k) { record(os, streamMetadata, path, gridAt(first + k), &records[std::size_t(k)]); });
      for (GridRecord& r : records) {
        if (r.direct)
          writeDirect(os, streamMetadata, r);
        else
          append(os, r);
        if (!os) throw std::runtime_error(fmt::format("{}: cannot write OpenVDB file: {}", path, failureReason()));
      }
    }
    openvdb::io::clearStreamMetadataPtr(os);
    return headerBytes;
  }

 private:
  // Grids alive at once, whatever the cores: a bound on the memory the write adds to the volume's
  // (each grid holds one value of every probe), and enough to keep 8 cores busy.
  static constexpr std::int32_t kGridsAtOnce = 16;

  struct GridRecord {
    std::stringstream bytes{std::ios::in | std::ios::out | std::ios::binary};
    openvdb::io::GridDescriptor descriptor;
    // A grid written straight into the file when its turn comes.
    openvdb::GridBase::ConstPtr direct;
  };

  // The grid's record as writeRecord puts it in a stream with the file's settings (copied from
  // `file`: version, compression, statistics, stream metadata), starting at position 0.
  void record(const std::ostream& file, openvdb::io::StreamMetadata::Ptr& fileLevel, const std::string& path,
              const BuiltGrid& built, GridRecord* r) const {
    const openvdb::GridBase::ConstPtr grid = built.grid;
    r->descriptor = openvdb::io::GridDescriptor(grid->getName(), grid->type(), grid->saveFloatAsHalf());
    if (built.direct) {
      r->direct = grid;
      return;
    }
    r->bytes.copyfmt(file);
    writeRecord(r->descriptor, *grid, r->bytes, fileLevel);
    if (!r->bytes) throw std::runtime_error(fmt::format("{}: cannot serialise grid '{}' in memory", path, grid->getName()));
  }

  // The grid's record written at the stream's position, in its turn.
  void writeDirect(std::ostream& os, openvdb::io::StreamMetadata::Ptr& fileLevel, GridRecord& r) const {
    writeRecord(r.descriptor, *r.direct, os, fileLevel);
    r.direct.reset();
  }

  // The grid's record at the stream's position, as Archive::writeGrid writes it to a seekable
  // stream but without the `file_delayed_load` metadata it adds to grids of our value types:
  // filling that compresses every leaf's values once more only to learn their compressed sizes
  // (about a quarter of default_room's write, measured), for readers that load a grid's leaves
  // lazily. Such readers still read these grids, as they read files written before OpenVDB 6.2.
  // `fileLevel` is the file's stream metadata, which `os` points to; a grid's is the file's with
  // the grid's own settings, and the file's is put back.
  void writeRecord(openvdb::io::GridDescriptor& gd, const openvdb::GridBase& grid, std::ostream& os,
                   openvdb::io::StreamMetadata::Ptr& fileLevel) const {
    struct RestoreFileLevel {
      std::ostream& os;
      openvdb::io::StreamMetadata::Ptr& meta;
      ~RestoreFileLevel() { openvdb::io::setStreamMetadataPtr(os, meta, /*transfer=*/false); }
    } restore{os, fileLevel};
    auto gridLevel = std::make_shared<openvdb::io::StreamMetadata>(*fileLevel);
    gridLevel->setHalfFloat(grid.saveFloatAsHalf());
    gridLevel->gridMetadata() = static_cast<const openvdb::MetaMap&>(grid);
    openvdb::io::setStreamMetadataPtr(os, gridLevel, /*transfer=*/false);

    gd.writeHeader(os);
    const std::int64_t positionsAt = std::int64_t(os.tellp());
    gd.writeStreamPos(os);  // placeholders, rewritten once the record's end is known
    gd.setGridPos(os.tellp());
    setGridCompression(os, grid);
    if (openvdb::io::getWriteGridStatsMetadata(os)) {
      const openvdb::GridBase::Ptr withStatistics = openvdb::ConstPtrCast<openvdb::GridBase>(grid.copyGrid());
      withStatistics->addStatsMetadata();
      withStatistics->insertMeta(openvdb::GridBase::META_FILE_COMPRESSION,
                                 openvdb::StringMetadata(openvdb::io::compressionToString(openvdb::io::getDataCompression(os))));
      withStatistics->writeMeta(os);
    } else {
      grid.writeMeta(os);
    }
    grid.writeTransform(os);
    grid.writeTopology(os);
    gd.setBlockPos(os.tellp());
    grid.writeBuffers(os);
    gd.setEndPos(os.tellp());
    os.seekp(positionsAt, std::ios_base::beg);
    gd.writeStreamPos(os);
    gd.seekToEnd(os);
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

// The distance maps of a level's stored bricks as one atlas (DistanceGrids::Atlas). The atlas of a
// brick spans 8·size × 8·size × 8 voxels, size² whole leaves, each filled in place. Saved as full
// floats: a leak-aware reading takes the variance as G − R², which half floats' rounding can swamp
// near a wall (2.6 % of a sample's irradiance, measured).
openvdb::Vec3SGrid::Ptr distanceAtlas(const Volume& volume, const std::vector<StoredBrick>& bricks) {
  using Leaf = openvdb::Vec3STree::LeafNodeType;
  const int size = volume.distanceMap.size, texels = size * size;
  std::vector<FloatColumn> columns;  // texel t's component c at 3t + c
  for (int t = 0; t < texels; ++t)
    for (int c = 0; c < 3; ++c) columns.push_back(floatColumn(volume, distanceTexelGrid(t, texels), c));
  auto grid = openvdb::Vec3SGrid::create(openvdb::Vec3s(0.0f));
  std::vector<std::unique_ptr<Leaf>> leaves{std::size_t(texels)};  // leaf (a, b) of a brick at a + size·b
  std::vector<openvdb::Vec3s*> values;                              // their buffers
  for (const StoredBrick& brick : bricks) {
    for (int b = 0; b < size; ++b)
      for (int a = 0; a < size; ++a)
        leaves[std::size_t(a + size * b)] = std::make_unique<Leaf>(
            openvdb::Coord(brick.origin.x() * size + kBrickSize * a, brick.origin.y() * size + kBrickSize * b,
                           brick.origin.z()),
            openvdb::Vec3s(0.0f), false);
    // Values written through the leaves' buffers (setValueOn checks, value by value, whether the
    // buffer is out of core), the active bits beside them.
    values.clear();
    for (const std::unique_ptr<Leaf>& leaf : leaves) values.push_back(leaf->buffer().data());
    for (const auto& [voxel, row] : brick.voxelRows) {
      const openvdb::Coord probe = Leaf::offsetToLocalCoord(voxel);
      for (int v = 0, t = 0; v < size; ++v)
        for (int u = 0; u < size; ++u, ++t) {
          const AtlasVoxel at = distanceAtlasVoxel(probe.x(), probe.y(), probe.z(), u, v, size);
          const std::size_t leaf = std::size_t(at.x / kBrickSize + size * (at.y / kBrickSize));
          const openvdb::Index offset =
              Leaf::coordToOffset(openvdb::Coord(int(at.x % kBrickSize), int(at.y % kBrickSize), int(at.z)));
          const FloatColumn* column = &columns[std::size_t(3 * t)];
          values[leaf][offset] = openvdb::Vec3s(column[0][row], column[1][row], column[2][row]);
          leaves[leaf]->setActiveState(offset, true);
        }
    }
    // A leaf beyond the grid's last probes (a brick cut by its edge) holds nothing.
    for (std::unique_ptr<Leaf>& leaf : leaves)
      if (!leaf->isEmpty()) grid->tree().addLeaf(leaf.release());
  }
  return grid;
}

// Where a level's grid `spec` lies: voxel (i, j, k) at the level's probe (i, j, k), or the atlas's
// size² voxels a probe in its cell's x and y.
openvdb::math::Transform::Ptr gridTransform(const Volume& volume, const VolumeGrid& spec) {
  const ProbeGrid& g = volume.grid;
  if (spec.kind == VolumeGrid::Kind::DistanceAtlas) {
    const double across = g.spacing / volume.distanceMap.size;
    return std::make_shared<openvdb::math::Transform>(std::make_shared<openvdb::math::ScaleTranslateMap>(
        openvdb::Vec3d(across, across, g.spacing), vec3d(g.origin)));
  }
  openvdb::math::Transform::Ptr transform = openvdb::math::Transform::createLinearTransform(g.spacing);
  transform->postTranslate(vec3d(g.origin));
  return transform;
}

// A level's grid `spec`: its stored bricks' voxels.
openvdb::GridBase::Ptr levelGrid(const Volume& volume, const std::vector<StoredBrick>& bricks, const VolumeGrid& spec) {
  if (spec.kind == VolumeGrid::Kind::DistanceAtlas) return distanceAtlas(volume, bricks);
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
                  distanceGridsWritten(first.distanceMap, VolumeFile::OpenVdb), first.keepsSkyDirect,
                  first.keepsSkyBounced);
  std::vector<std::vector<StoredBrick>> bricks;
  for (const LevelGrids& level : levels) bricks.push_back(storedBrickVoxels(*level.volume, level.stored));
  const auto gridAt = [&](std::int32_t index) {
    const std::size_t n = std::size_t(index) / specs.size();
    const Volume& volume = *levels[n].volume;
    const VolumeGrid& spec = specs[std::size_t(index) % specs.size()];
    openvdb::GridBase::Ptr grid = levelGrid(volume, bricks[n], spec);
    grid->setName(levels[n].prefix + spec.name);
    grid->setTransform(gridTransform(volume, spec));
    // The atlas holds most of a volume's bytes (N² texels a probe): built and serialised beside
    // fifteen other grids, with its record in a buffer of its own, it would be alive twice.
    return BuiltGrid{grid, spec.kind == VolumeGrid::Kind::DistanceAtlas};
  };

  AtomicFile out(path);
  try {
    errno = 0;
    std::ofstream file(out.temporaryPath(), std::ios::binary | std::ios::trunc);
    if (!file)
      throw std::runtime_error(fmt::format("{}: cannot create '{}': {}", path, out.temporaryPath(), failureReason()));
    const std::uint64_t headerBytes =
        GridByGridArchive().writeGrids(file, path, metadata, std::int32_t(specs.size() * levels.size()), gridAt);
    file.close();
    if (!file) throw std::runtime_error(fmt::format("{}: cannot write OpenVDB file: {}", path, failureReason()));
    deriveVdbUuid(out.temporaryPath());
    sealVdbChecksum(out.temporaryPath(), headerBytes);
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
