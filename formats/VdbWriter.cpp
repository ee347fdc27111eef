#include "formats/VdbWriter.h"

#include <fmt/format.h>
#include <openvdb/openvdb.h>

#include <cmath>

#include "formats/AtomicFile.h"
#include "formats/VolumeLayout.h"
#include "formats/VolumeMetadata.h"

namespace baker {

void writeVdb(const Volume& volume, const Basis& basis, const std::string& path) {
  for (std::size_t i = 0; i < volume.coefficients.size(); ++i)
    if (!std::isfinite(volume.coefficients[i]))
      throw std::runtime_error(fmt::format("internal error: probe {} has a non-finite coefficient; nothing written",
                                           i / volume.coefficientsPerProbe));
  openvdb::initialize();
  const ProbeGrid& g = volume.grid;
  openvdb::math::Transform::Ptr transform = openvdb::math::Transform::createLinearTransform(g.spacing);
  transform->postTranslate(openvdb::Vec3d(g.origin.x(), g.origin.y(), g.origin.z()));

  openvdb::GridPtrVec grids;
  for (const CoefficientGrid& spec : coefficientGrids(basis)) {
    openvdb::GridBase::Ptr grid;
    if (spec.isVector) {
      auto vec = openvdb::Vec3SGrid::create(openvdb::Vec3s(0.0f));
      auto access = vec->getAccessor();
      const int offsets[3] = {basis.coefficientOffset(0), basis.coefficientOffset(1), basis.coefficientOffset(2)};
      for (int k = 0; k < g.dims.z(); ++k)
        for (int j = 0; j < g.dims.y(); ++j)
          for (int i = 0; i < g.dims.x(); ++i) {
            const float* c = volume.probe(g.linearIndex(i, j, k));
            access.setValue(openvdb::Coord(i, j, k), openvdb::Vec3s(c[offsets[0] + spec.function],
                                                                   c[offsets[1] + spec.function],
                                                                   c[offsets[2] + spec.function]));
          }
      grid = vec;
    } else {
      auto scalar = openvdb::FloatGrid::create(0.0f);
      auto access = scalar->getAccessor();
      const int offset = basis.coefficientOffset(spec.channel) + spec.function;
      for (int k = 0; k < g.dims.z(); ++k)
        for (int j = 0; j < g.dims.y(); ++j)
          for (int i = 0; i < g.dims.x(); ++i)
            access.setValue(openvdb::Coord(i, j, k), volume.probe(g.linearIndex(i, j, k))[offset]);
      grid = scalar;
    }
    grid->setName(spec.name);
    grid->setTransform(transform->copy());
    grids.push_back(grid);
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
