#include "formats/VolumeHeader.h"

#include <fmt/format.h>

#include <cmath>

#include "bake/BasisRegistry.h"
#include "common/Error.h"
#include "formats/VolumeLayout.h"
#include "formats/VolumeMetadata.h"

namespace baker {

// Far beyond any bake (--spacing refuses grids above 2^27 probes) and small enough that a
// corrupted size is refused before it allocates.
constexpr double kMaxProbesRead = double(1 << 28);

Volume VolumeHeader::emptyVolume(const std::string& path) const {
  const std::unique_ptr<Basis> basis = makeBasis(basisName);
  if (coefficientsPerProbe != basis->totalCoefficients())
    throw InputError(fmt::format("{}: baker.coefficients_per_probe is {}, but {} has {}", path, coefficientsPerProbe,
                                 basisName, basis->totalCoefficients()));
  if (visibilityPerProbe != 0 && visibilityPerProbe != basis->functions(0).count())
    throw InputError(fmt::format("{}: baker.visibility_per_probe is {}, but {} has {} functions in channel 0", path,
                                 visibilityPerProbe, basisName, basis->functions(0).count()));
  const Eigen::Vector3i& d = grid.dims;
  if (d.x() <= 0 || d.y() <= 0 || d.z() <= 0 || double(d.x()) * d.y() * d.z() > kMaxProbesRead)
    throw InputError(fmt::format("{}: baker.dims ({}, {}, {}) is not a valid grid size", path, d.x(), d.y(), d.z()));
  if (!(grid.spacing > 0.0) || !std::isfinite(grid.spacing))
    throw InputError(fmt::format("{}: baker.spacing must be a positive number, got {}", path, grid.spacing));
  if (!grid.origin.allFinite()) throw InputError(fmt::format("{}: baker.origin is not finite", path));
  Volume volume;
  volume.grid = grid;
  volume.basisName = basisName;
  volume.coefficientsPerProbe = coefficientsPerProbe;
  volume.visibilityPerProbe = visibilityPerProbe;
  readSettings(text, volume);
  prepareForReading(volume, hasProbeStates);
  return volume;
}

void requireFiniteValues(const Volume& v, const std::string& path) {
  for (std::size_t i = 0; i < v.coefficients.size(); ++i)
    if (!std::isfinite(v.coefficients[i]))
      throw InputError(fmt::format("{}: probe {} has a non-finite coefficient", path, i / v.coefficientsPerProbe));
  for (std::size_t i = 0; i < v.visibility.size(); ++i)
    if (!std::isfinite(v.visibility[i]))
      throw InputError(fmt::format("{}: probe {} has a non-finite visibility value", path, i / v.visibilityPerProbe));
  for (const Eigen::Vector3f& o : v.offsets)
    if (!o.allFinite()) throw InputError(fmt::format("{}: a probe offset is not finite", path));
}

}  // namespace baker
