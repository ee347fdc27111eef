#include "formats/VolumeReader.h"

#include <fmt/format.h>
#include <openvdb/openvdb.h>

#include <filesystem>

#include "bake/BasisRegistry.h"
#include "common/Error.h"
#include "formats/VolumeLayout.h"

namespace baker {
namespace {

template <typename T>
T required(const openvdb::MetaMap& meta, const std::string& key, const std::string& path) {
  auto value = meta.getMetadata<openvdb::TypedMetadata<T>>(key);
  if (!value) throw InputError(fmt::format("{}: metadata '{}' is missing or has the wrong type", path, key));
  return value->value();
}

template <typename GridType>
typename GridType::Ptr typedGrid(openvdb::io::File& file, const std::string& name, const std::string& path) {
  if (!file.hasGrid(name)) throw InputError(fmt::format("{}: grid '{}' is missing", path, name));
  auto grid = openvdb::gridPtrCast<GridType>(file.readGrid(name));
  if (!grid) throw InputError(fmt::format("{}: grid '{}' has the wrong value type", path, name));
  return grid;
}

template <typename Visit>
void forEachProbe(const ProbeGrid& g, Visit visit) {
  for (int k = 0; k < g.dims.z(); ++k)
    for (int j = 0; j < g.dims.y(); ++j)
      for (int i = 0; i < g.dims.x(); ++i) visit(i, j, k, g.linearIndex(i, j, k));
}

}  // namespace

Volume readVolume(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw InputError(fmt::format("{}: volume file does not exist", path));
  openvdb::initialize();
  try {
    openvdb::io::File file(path);
    file.open();
    openvdb::MetaMap::Ptr meta = file.getMetadata();
    Volume volume;
    volume.basisName = required<std::string>(*meta, "baker.basis", path);
    const auto basis = makeBasis(volume.basisName);
    volume.coefficientsPerProbe = required<int>(*meta, "baker.coefficients_per_probe", path);
    if (volume.coefficientsPerProbe != basis->totalCoefficients())
      throw InputError(fmt::format("{}: baker.coefficients_per_probe is {}, but {} has {}", path,
                                   volume.coefficientsPerProbe, volume.basisName, basis->totalCoefficients()));
    const openvdb::Vec3i dims = required<openvdb::Vec3i>(*meta, "baker.dims", path);
    const openvdb::Vec3d origin = required<openvdb::Vec3d>(*meta, "baker.origin", path);
    volume.grid.dims = Eigen::Vector3i(dims.x(), dims.y(), dims.z());
    volume.grid.origin = Eigen::Vector3d(origin.x(), origin.y(), origin.z());
    volume.grid.spacing = required<double>(*meta, "baker.spacing", path);
    if (dims.x() <= 0 || dims.y() <= 0 || dims.z() <= 0 || double(dims.x()) * dims.y() * dims.z() > double(1 << 30))
      throw InputError(fmt::format("{}: baker.dims ({}, {}, {}) is not a valid grid size", path, dims.x(), dims.y(), dims.z()));
    if (!(volume.grid.spacing > 0.0)) throw InputError(fmt::format("{}: baker.spacing must be positive", path));
    const std::string prefix = "baker.setting.";
    for (auto it = meta->beginMeta(); it != meta->endMeta(); ++it)
      if (it->first.rfind(prefix, 0) == 0) volume.settings[it->first.substr(prefix.size())] = it->second->str();

    const ProbeGrid& g = volume.grid;
    volume.coefficients.assign(std::size_t(g.probeCount()) * volume.coefficientsPerProbe, 0.0f);
    for (const CoefficientGrid& spec : coefficientGrids(*basis)) {
      if (!file.hasGrid(spec.name)) throw InputError(fmt::format("{}: grid '{}' is missing", path, spec.name));
      openvdb::GridBase::Ptr base = file.readGrid(spec.name);
      if (spec.isVector) {
        auto grid = openvdb::gridPtrCast<openvdb::Vec3SGrid>(base);
        if (!grid) throw InputError(fmt::format("{}: grid '{}' is not a Vec3s grid", path, spec.name));
        auto access = grid->getConstAccessor();
        for (int k = 0; k < g.dims.z(); ++k)
          for (int j = 0; j < g.dims.y(); ++j)
            for (int i = 0; i < g.dims.x(); ++i) {
              const openvdb::Vec3s v = access.getValue(openvdb::Coord(i, j, k));
              float* c = volume.coefficients.data() + g.linearIndex(i, j, k) * volume.coefficientsPerProbe;
              for (int ch = 0; ch < 3; ++ch) c[basis->coefficientOffset(ch) + spec.function] = v[ch];
            }
      } else {
        auto grid = openvdb::gridPtrCast<openvdb::FloatGrid>(base);
        if (!grid) throw InputError(fmt::format("{}: grid '{}' is not a float grid", path, spec.name));
        auto access = grid->getConstAccessor();
        const int offset = basis->coefficientOffset(spec.channel) + spec.function;
        for (int k = 0; k < g.dims.z(); ++k)
          for (int j = 0; j < g.dims.y(); ++j)
            for (int i = 0; i < g.dims.x(); ++i)
              volume.coefficients[g.linearIndex(i, j, k) * volume.coefficientsPerProbe + offset] =
                  access.getValue(openvdb::Coord(i, j, k));
      }
    }
    // Sky visibility and probe validity: every bake writes them; volumes from before they existed have neither.
    auto visibilityCount = meta->getMetadata<openvdb::Int32Metadata>("baker.visibility_per_probe");
    volume.visibilityPerProbe = visibilityCount ? visibilityCount->value() : 0;
    if (volume.visibilityPerProbe != 0 && volume.visibilityPerProbe != basis->functions(0).count())
      throw InputError(fmt::format("{}: baker.visibility_per_probe is {}, but {} has {} functions in channel 0", path,
                                   volume.visibilityPerProbe, volume.basisName, basis->functions(0).count()));
    volume.visibility.assign(std::size_t(g.probeCount()) * volume.visibilityPerProbe, 0.0f);
    for (int f = 0; f < volume.visibilityPerProbe; ++f) {
      auto grid = typedGrid<openvdb::FloatGrid>(file, visibilityGridName(f), path);
      auto access = grid->getConstAccessor();
      forEachProbe(g, [&](int i, int j, int k, std::int64_t p) {
        volume.visibility[p * volume.visibilityPerProbe + f] = access.getValue(openvdb::Coord(i, j, k));
      });
    }
    if (file.hasGrid(kProbeStateGrid)) {
      auto states = typedGrid<openvdb::Int32Grid>(file, kProbeStateGrid, path);
      auto offsets = typedGrid<openvdb::Vec3SGrid>(file, kProbeOffsetGrid, path);
      volume.states.assign(g.probeCount(), ProbeState::Valid);
      volume.offsets.assign(g.probeCount(), Eigen::Vector3f::Zero());
      auto stateAccess = states->getConstAccessor();
      auto offsetAccess = offsets->getConstAccessor();
      forEachProbe(g, [&](int i, int j, int k, std::int64_t p) {
        const int state = stateAccess.getValue(openvdb::Coord(i, j, k));
        if (state < 0 || state > 2)
          throw InputError(fmt::format("{}: grid '{}' holds {} at ({}, {}, {}); states are 0, 1 or 2", path,
                                       kProbeStateGrid, state, i, j, k));
        volume.states[p] = ProbeState(state);
        const openvdb::Vec3s o = offsetAccess.getValue(openvdb::Coord(i, j, k));
        volume.offsets[p] = Eigen::Vector3f(o.x(), o.y(), o.z());
      });
    }
    file.close();
    return volume;
  } catch (const openvdb::Exception& e) {
    throw InputError(fmt::format("{}: not a readable OpenVDB volume: {}", path, e.what()));
  }
}

}  // namespace baker
