#include "formats/VdbReader.h"

#include <fmt/format.h>
#include <openvdb/openvdb.h>

#include "basis/BasisRegistry.h"
#include "common/Error.h"
#include "formats/VdbChecksum.h"
#include "formats/VolumeHeader.h"
#include "formats/VolumeLayout.h"
#include "formats/VolumeMetadata.h"

namespace baker {
namespace {

template <typename T>
T required(const openvdb::MetaMap& meta, const std::string& key, const std::string& path) {
  auto value = meta.getMetadata<openvdb::TypedMetadata<T>>(key);
  if (!value) throw InputError(fmt::format("{}: metadata '{}' is missing or has the wrong type", path, key));
  return value->value();
}

// A voxel of a part read as its own bricks only that lies in another shard's brick.
InputError voxelOutsideShard(const std::string& path, const std::string& name, const Volume& v, std::int64_t p) {
  return InputError(fmt::format("{}: grid '{}' holds probe {}, outside the bricks of its shard {}", path, name, p,
                                shardName(*v.shard)));
}

// Copies the active voxels of one grid into the volume, refusing voxels outside the grid.
template <typename GridType, typename Store>
void readVoxels(openvdb::io::File& file, const std::string& name, const ProbeGrid& g, const std::string& path,
                Store store) {
  if (!file.hasGrid(name)) throw InputError(fmt::format("{}: grid '{}' is missing", path, name));
  auto grid = openvdb::gridPtrCast<GridType>(file.readGrid(name));
  if (!grid) throw InputError(fmt::format("{}: grid '{}' has the wrong value type", path, name));
  for (auto it = grid->cbeginValueOn(); it; ++it) {
    const openvdb::Coord c = it.getCoord();
    if (c.x() < 0 || c.y() < 0 || c.z() < 0 || c.x() >= g.dims.x() || c.y() >= g.dims.y() || c.z() >= g.dims.z())
      throw InputError(fmt::format("{}: grid '{}' has a voxel at ({}, {}, {}), outside the {} × {} × {} probes", path,
                                   name, c.x(), c.y(), c.z(), g.dims.x(), g.dims.y(), g.dims.z()));
    store(g.linearIndex(c.x(), c.y(), c.z()), *it);
  }
}

}  // namespace

Volume readVdb(const std::string& path, PartReading parts) {
  requireVdbChecksum(path);
  openvdb::initialize();
  try {
    openvdb::io::File file(path);
    file.open();
    openvdb::MetaMap::Ptr meta = file.getMetadata();
    VolumeHeader header;
    header.basisName = required<std::string>(*meta, "baker.basis", path);
    header.coefficientsPerProbe = required<int>(*meta, "baker.coefficients_per_probe", path);
    auto visibility = meta->getMetadata<openvdb::Int32Metadata>("baker.visibility_per_probe");
    header.visibilityPerProbe = visibility ? visibility->value() : 0;
    const openvdb::Vec3i dims = required<openvdb::Vec3i>(*meta, "baker.dims", path);
    const openvdb::Vec3d origin = required<openvdb::Vec3d>(*meta, "baker.origin", path);
    header.grid.dims = Eigen::Vector3i(dims.x(), dims.y(), dims.z());
    header.grid.origin = Eigen::Vector3d(origin.x(), origin.y(), origin.z());
    header.grid.spacing = required<double>(*meta, "baker.spacing", path);
    header.hasProbeStates = file.hasGrid("probe_state");
    for (auto it = meta->beginMeta(); it != meta->endMeta(); ++it) header.text.push_back({it->first, it->second->str()});

    Volume volume = header.emptyVolume(path, parts);
    const std::unique_ptr<Basis> basis = makeBasis(volume.basisName);
    const ProbeGrid& g = volume.grid;
    for (const VolumeGrid& spec : volumeGrids(*basis, volume.visibilityPerProbe, header.hasProbeStates)) {
      if (spec.kind == VolumeGrid::Kind::ProbeState)
        readVoxels<openvdb::Int32Grid>(file, spec.name, g, path, [&](std::int64_t p, int state) {
          if (state < 0 || state > 2)
            throw InputError(fmt::format("{}: grid 'probe_state' holds {}; states are 0, 1 or 2", path, state));
          const std::int64_t row = volume.rowOf(p);
          if (row < 0) throw voxelOutsideShard(path, spec.name, volume, p);
          volume.states[row] = ProbeState(state);
        });
      else if (spec.components == 3)
        readVoxels<openvdb::Vec3SGrid>(file, spec.name, g, path, [&](std::int64_t p, const openvdb::Vec3s& v) {
          for (int c = 0; c < 3; ++c)
            if (!setGridValue(volume, spec, c, p, v[c])) throw voxelOutsideShard(path, spec.name, volume, p);
        });
      else
        readVoxels<openvdb::FloatGrid>(file, spec.name, g, path, [&](std::int64_t p, float v) {
          if (!setGridValue(volume, spec, 0, p, v)) throw voxelOutsideShard(path, spec.name, volume, p);
        });
    }
    file.close();
    requireFiniteValues(volume, path);
    return volume;
  } catch (const openvdb::Exception& e) {
    throw InputError(fmt::format("{}: not a readable OpenVDB volume: {}", path, e.what()));
  }
}

}  // namespace baker
