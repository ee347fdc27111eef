#include "formats/VdbWriter.h"

#include <fmt/format.h>
#include <openvdb/openvdb.h>

#include <cmath>

#include "formats/AtomicFile.h"
#include "formats/VdbChecksum.h"
#include "formats/VolumeLayout.h"
#include "formats/VolumeMetadata.h"

namespace baker {
namespace {

// A grid holding the voxels of the stored bricks, every one active (a constant value is data
// here, not background).
template <typename GridType, typename ValueAt>
typename GridType::Ptr sparseGrid(const Volume& v, const std::vector<bool>& stored, ValueAt valueAt) {
  auto grid = GridType::create(typename GridType::ValueType(0));
  auto access = grid->getAccessor();
  const ProbeGrid& g = v.grid;
  for (int k = 0; k < g.dims.z(); ++k)
    for (int j = 0; j < g.dims.y(); ++j)
      for (int i = 0; i < g.dims.x(); ++i)
        if (stored[brickOf(g, i, j, k)]) access.setValue(openvdb::Coord(i, j, k), valueAt(g.linearIndex(i, j, k)));
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

  openvdb::GridPtrVec grids;
  for (const VolumeGrid& spec : volumeGrids(basis, volume.visibilityPerProbe, !volume.states.empty())) {
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
    grids.push_back(grid);
  }

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
