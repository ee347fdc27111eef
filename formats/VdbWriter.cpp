#include "formats/VdbWriter.h"

#include <fmt/format.h>
#include <openvdb/openvdb.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "bake/Baker.h"
#include "formats/AtomicFile.h"
#include "formats/VdbChecksum.h"
#include "formats/VolumeLayout.h"
#include "formats/VolumeMetadata.h"

namespace baker {
namespace {

// A grid holding the voxels of the stored bricks, every one active (a constant value is data
// here, not background). A brick is exactly one leaf node, filled in place: going voxel by
// voxel through an accessor costs several times as much.
template <typename GridType, typename ValueAt>
typename GridType::Ptr sparseGrid(const Volume& v, const std::vector<bool>& stored, ValueAt valueAt) {
  using LeafType = typename GridType::TreeType::LeafNodeType;
  static_assert(LeafType::DIM == kBrickSize, "a brick is one OpenVDB leaf");
  auto grid = GridType::create(typename GridType::ValueType(0));
  const ProbeGrid& g = v.grid;
  const Eigen::Vector3i bricks = (g.dims.array() + kBrickSize - 1) / kBrickSize;
  for (int bk = 0; bk < bricks.z(); ++bk)
    for (int bj = 0; bj < bricks.y(); ++bj)
      for (int bi = 0; bi < bricks.x(); ++bi) {
        const openvdb::Coord origin(bi * kBrickSize, bj * kBrickSize, bk * kBrickSize);
        if (!stored[brickOf(g, origin.x(), origin.y(), origin.z())]) continue;
        auto leaf = std::make_unique<LeafType>(origin, typename GridType::ValueType(0), false);
        for (int k = origin.z(); k < std::min(origin.z() + kBrickSize, g.dims.z()); ++k)
          for (int j = origin.y(); j < std::min(origin.y() + kBrickSize, g.dims.y()); ++j)
            for (int i = origin.x(); i < std::min(origin.x() + kBrickSize, g.dims.x()); ++i)
              leaf->setValueOn(LeafType::coordToOffset(openvdb::Coord(i, j, k)), valueAt(g.linearIndex(i, j, k)));
        grid->tree().addLeaf(leaf.release());
      }
  return grid;
}

openvdb::MetaMap fileMetadata(const Volume& v, const Basis& basis) {
  openvdb::MetaMap meta;
  for (const auto& [key, value] : describingMetadata(v, basis)) meta.insertMeta(key, openvdb::StringMetadata(value));
  const ProbeGrid& g = v.grid;
  meta.insertMeta("baker.coefficients_per_probe", openvdb::Int32Metadata(v.coefficientsPerProbe));
  meta.insertMeta("baker.visibility_per_probe", openvdb::Int32Metadata(v.visibilityPerProbe));
  meta.insertMeta("baker.dims", openvdb::Vec3IMetadata(openvdb::Vec3i(g.dims.x(), g.dims.y(), g.dims.z())));
  meta.insertMeta("baker.origin", openvdb::Vec3DMetadata(openvdb::Vec3d(g.origin.x(), g.origin.y(), g.origin.z())));
  meta.insertMeta("baker.spacing", openvdb::DoubleMetadata(g.spacing));
  meta.insertMeta(kVdbChecksumKey, openvdb::StringMetadata(kVdbChecksumPlaceholder));
  return meta;
}

}  // namespace

void writeVdb(const Volume& volume, const Basis& basis, const std::string& path) {
  requireFiniteVolume(volume);
  openvdb::initialize();
  const ProbeGrid& g = volume.grid;
  openvdb::math::Transform::Ptr transform = openvdb::math::Transform::createLinearTransform(g.spacing);
  transform->postTranslate(openvdb::Vec3d(g.origin.x(), g.origin.y(), g.origin.z()));
  const std::vector<bool> stored = storedBricks(volume);

  // Grids are independent: built in parallel, written in order.
  const std::vector<VolumeGrid> specs = volumeGrids(basis, volume.visibilityPerProbe, !volume.states.empty());
  openvdb::GridPtrVec grids(specs.size());
  tbb::parallel_for(std::size_t(0), specs.size(), [&](std::size_t index) {
    const VolumeGrid& spec = specs[index];
    openvdb::GridBase::Ptr grid;
    if (spec.kind == VolumeGrid::Kind::ProbeState)
      grid = sparseGrid<openvdb::Int32Grid>(volume, stored, [&](std::int64_t p) { return int(volume.states[p]); });
    else if (spec.components == 3)
      grid = sparseGrid<openvdb::Vec3SGrid>(volume, stored, [&](std::int64_t p) {
        return openvdb::Vec3s(gridValue(volume, spec, 0, p), gridValue(volume, spec, 1, p), gridValue(volume, spec, 2, p));
      });
    else
      grid = sparseGrid<openvdb::FloatGrid>(volume, stored, [&](std::int64_t p) { return gridValue(volume, spec, 0, p); });
    grid->setName(spec.name);
    grid->setTransform(transform->copy());
    grids[index] = grid;
  });

  AtomicFile out(path);
  try {
    openvdb::io::File file(out.temporaryPath());
    file.write(grids, fileMetadata(volume, basis));
    file.close();
    sealVdbChecksum(out.temporaryPath());
  } catch (const openvdb::Exception& e) {
    throw std::runtime_error(fmt::format("{}: cannot write OpenVDB file: {}", path, e.what()));
  }
  out.commit();
}

}  // namespace baker
