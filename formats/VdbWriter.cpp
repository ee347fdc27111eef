#include "formats/VdbWriter.h"

#include <fmt/format.h>
#include <openvdb/openvdb.h>

#include <cmath>

#include "formats/AtomicFile.h"
#include "formats/VolumeLayout.h"
#include "formats/VolumeMetadata.h"

namespace baker {

namespace {

// A grid with one voxel per probe, every voxel active (a constant value is data here, not background).
template <typename GridType, typename ValueAt>
typename GridType::Ptr denseGrid(const ProbeGrid& g, const std::string& name, const openvdb::math::Transform& transform,
                                 ValueAt valueAt) {
  auto grid = GridType::create(typename GridType::ValueType(0));
  auto access = grid->getAccessor();
  for (int k = 0; k < g.dims.z(); ++k)
    for (int j = 0; j < g.dims.y(); ++j)
      for (int i = 0; i < g.dims.x(); ++i) access.setValue(openvdb::Coord(i, j, k), valueAt(g.linearIndex(i, j, k)));
  grid->setName(name);
  grid->setTransform(transform.copy());
  return grid;
}

void requireFinite(const std::vector<float>& values, int perProbe, const char* what) {
  for (std::size_t i = 0; i < values.size(); ++i)
    if (!std::isfinite(values[i]))
      throw std::runtime_error(
          fmt::format("internal error: probe {} has a non-finite {}; nothing written", i / perProbe, what));
}

}  // namespace

void writeVdb(const Volume& volume, const Basis& basis, const std::string& path) {
  requireFinite(volume.coefficients, volume.coefficientsPerProbe, "coefficient");
  requireFinite(volume.visibility, std::max(1, volume.visibilityPerProbe), "visibility coefficient");
  openvdb::initialize();
  const ProbeGrid& g = volume.grid;
  openvdb::math::Transform::Ptr transform = openvdb::math::Transform::createLinearTransform(g.spacing);
  transform->postTranslate(openvdb::Vec3d(g.origin.x(), g.origin.y(), g.origin.z()));

  openvdb::GridPtrVec grids;
  for (const CoefficientGrid& spec : coefficientGrids(basis)) {
    if (spec.isVector) {
      const int offsets[3] = {basis.coefficientOffset(0) + spec.function, basis.coefficientOffset(1) + spec.function,
                              basis.coefficientOffset(2) + spec.function};
      grids.push_back(denseGrid<openvdb::Vec3SGrid>(g, spec.name, *transform, [&](std::int64_t p) {
        const float* c = volume.probe(p);
        return openvdb::Vec3s(c[offsets[0]], c[offsets[1]], c[offsets[2]]);
      }));
    } else {
      const int offset = basis.coefficientOffset(spec.channel) + spec.function;
      grids.push_back(denseGrid<openvdb::FloatGrid>(g, spec.name, *transform,
                                                    [&](std::int64_t p) { return volume.probe(p)[offset]; }));
    }
  }
  for (int f = 0; f < volume.visibilityPerProbe; ++f)
    grids.push_back(denseGrid<openvdb::FloatGrid>(g, visibilityGridName(f), *transform, [&](std::int64_t p) {
      return volume.visibility[p * volume.visibilityPerProbe + f];
    }));
  if (!volume.states.empty()) {
    grids.push_back(denseGrid<openvdb::Int32Grid>(g, kProbeStateGrid, *transform,
                                                  [&](std::int64_t p) { return int(volume.states[p]); }));
    grids.push_back(denseGrid<openvdb::Vec3SGrid>(g, kProbeOffsetGrid, *transform, [&](std::int64_t p) {
      const Eigen::Vector3f& o = volume.offsets[p];
      return openvdb::Vec3s(o.x(), o.y(), o.z());
    }));
  }

  AtomicFile out(path);
  try {
    openvdb::io::File file(out.temporaryPath());
    file.write(grids, volumeMetadata(volume, basis));
    file.close();
  } catch (const openvdb::Exception& e) {
    throw std::runtime_error(fmt::format("{}: cannot write OpenVDB file: {}", path, e.what()));
  }
  out.commit();
}

}  // namespace baker
