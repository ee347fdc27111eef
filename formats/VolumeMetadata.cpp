#include "formats/VolumeMetadata.h"

namespace baker {

openvdb::MetaMap volumeMetadata(const Volume& volume, const Basis& basis) {
  openvdb::MetaMap meta;
  meta.insertMeta("baker.version", openvdb::StringMetadata(BAKER_VERSION));
  meta.insertMeta("baker.basis", openvdb::StringMetadata(basis.name()));
  meta.insertMeta("baker.quantity", openvdb::StringMetadata("irradiance"));
  meta.insertMeta("baker.color_space", openvdb::StringMetadata(colorSpaceName(basis.colorSpace())));
  meta.insertMeta("baker.coefficients_per_probe", openvdb::Int32Metadata(basis.totalCoefficients()));
  meta.insertMeta("baker.visibility_per_probe", openvdb::Int32Metadata(volume.visibilityPerProbe));
  const ProbeGrid& g = volume.grid;
  meta.insertMeta("baker.dims", openvdb::Vec3IMetadata(openvdb::Vec3i(g.dims.x(), g.dims.y(), g.dims.z())));
  meta.insertMeta("baker.origin", openvdb::Vec3DMetadata(openvdb::Vec3d(g.origin.x(), g.origin.y(), g.origin.z())));
  meta.insertMeta("baker.spacing", openvdb::DoubleMetadata(g.spacing));
  for (const auto& [key, value] : volume.settings) meta.insertMeta("baker.setting." + key, openvdb::StringMetadata(value));
  return meta;
}

}  // namespace baker
