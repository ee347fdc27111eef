#include "formats/VolumeHeader.h"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>

#include "basis/BasisRegistry.h"
#include "common/Error.h"
#include "formats/VolumeLayout.h"
#include "formats/VolumeMetadata.h"
#include "volume/LevelGrids.h"
#include "volume/MemoryEstimate.h"

namespace baker {

// The oldest format whose keys still mean what this reader takes them to mean.
constexpr int kOldestFormatRead = 2;

namespace {

// The file's format version, refused unless this reader knows it.
int knownFormatVersion(const std::vector<std::pair<std::string, std::string>>& text, const std::string& path) {
  const auto entry = std::find_if(text.begin(), text.end(), [](const auto& e) { return e.first == "baker.format_version"; });
  if (entry == text.end()) throw InputError(fmt::format("{}: baker.format_version is missing", path));
  int version = 0;
  const auto [end, error] = std::from_chars(entry->second.data(), entry->second.data() + entry->second.size(), version);
  if (error != std::errc() || end != entry->second.data() + entry->second.size())
    throw InputError(fmt::format("{}: baker.format_version \"{}\" is not a whole number", path, entry->second));
  if (version > kNewestFormatVersion)
    throw InputError(fmt::format("{}: baker.format_version is {}: written by a newer baker (this one reads formats {} to "
                                 "{})", path, version, kOldestFormatRead, kNewestFormatVersion));
  if (version < kOldestFormatRead)
    throw InputError(fmt::format("{}: baker.format_version is {}: too old to read (formats {} to {}); bake it again",
                                 path, version, kOldestFormatRead, kNewestFormatVersion));
  return version;
}

// A map held in RGB texel grids came with format 6, as an atlas with format 7, and those formats
// hold a map with the sky's shares no other way: a file that says otherwise has lost or gained the
// key.
void requireDistanceGridsOfVersion(const std::vector<std::pair<std::string, std::string>>& text, int version,
                                   const Volume& volume, const std::string& path) {
  const DistanceGrids form = distanceGridsInFile(text);
  const int since = form == DistanceGrids::Atlas         ? kAtlasFormatVersion
                    : form == DistanceGrids::RgbPerTexel ? kTexelGridsFormatVersion
                                                         : 0;
  if (version < since)
    throw InputError(fmt::format("{}: {} has \"texel_grids\": \"{}\" in a file of format {}; it came with format {}",
                                 path, kDistanceMapKey, form == DistanceGrids::Atlas ? "atlas" : "rgb", version, since));
  if (form == DistanceGrids::ScalarPerValue && version >= kTexelGridsFormatVersion &&
      volume.distanceMomentsPerProbe() > 0 && volume.distanceMap.skyVisibility)
    throw InputError(fmt::format("{}: {} has no \"texel_grids\", which a file of format {} holding the sky's shares "
                                 "has", path, kDistanceMapKey, version));
}

}  // namespace

Volume VolumeHeader::emptyVolume(const std::string& path, PartReading parts) const {
  const int version = knownFormatVersion(text, path);
  Volume settingsOnly;
  readSettings(text, settingsOnly);
  const std::unique_ptr<Basis> basis = basisInFile(basisName, settingsOnly.settings, path);
  if (coefficientsPerProbe != basis->totalCoefficients())
    throw InputError(fmt::format("{}: baker.coefficients_per_probe is {}, but {} has {}", path, coefficientsPerProbe,
                                 basisName, basis->totalCoefficients()));
  if (visibilityPerProbe != 0 && visibilityPerProbe != basis->functions(0).count())
    throw InputError(fmt::format("{}: baker.visibility_per_probe is {}, but {} has {} functions in channel 0", path,
                                 visibilityPerProbe, basisName, basis->functions(0).count()));
  const Eigen::Vector3i& d = grid.dims;
  const double gridProbes = double(d.x()) * d.y() * d.z();
  if (d.minCoeff() <= 0 || d.maxCoeff() > kMaxProbesPerAxis ||
      gridProbes > (heldBricks ? kMaxLevelGridProbes : kMaxProbesRead) ||
      (heldBricks && double(grid.brickCount()) > kMaxLevelBricks))
    throw InputError(fmt::format("{}: baker.dims ({}, {}, {}) is not a valid grid size", path, d.x(), d.y(), d.z()));
  if (heldBricks)
    for (const std::int64_t b : *heldBricks)
      if (b < 0 || b >= grid.brickCount())
        throw InputError(fmt::format("{}: a brick of a level lies outside its {} × {} × {} probes", path, d.x(), d.y(), d.z()));
  const double heldProbes = heldBricks ? double(heldBricks->size()) * kBrickSize * kBrickSize * kBrickSize : gridProbes;
  if (heldProbes > kMaxProbesRead)
    throw InputError(fmt::format("{}: {:.3g} probes held, beyond the {:.3g} a volume may hold", path, heldProbes, kMaxProbesRead));
  // Half of the bake's estimate: reading holds the volume once (a part read as its own bricks
  // holds less, but the merge reading it holds the whole volume). Checked before allocating, so
  // that a damaged size is refused rather than exhausting memory.
  Volume volume;
  readDistanceMap(text, volume, path);
  requireDistanceGridsOfVersion(text, version, volume, path);
  readSky(text, volume, path);
  readSkyDirect(text, volume, path);
  const double needed =
      volumeMemoryBytes(std::min(heldProbes, gridProbes), *basis, volume.distanceMomentsPerProbe()) / 2;
  if (needed > double(physicalMemoryBytes()))
    throw InputError(fmt::format("{}: baker.dims ({}, {}, {}) in {} would need {:.3g} GiB, more than this machine's "
                                 "memory", path, d.x(), d.y(), d.z(), basisName, needed / double(1ull << 30)));
  if (!(grid.spacing > 0.0) || !std::isfinite(grid.spacing))
    throw InputError(fmt::format("{}: baker.spacing must be a positive number, got {}", path, grid.spacing));
  if (!grid.origin.allFinite()) throw InputError(fmt::format("{}: baker.origin is not finite", path));
  volume.grid = grid;
  volume.basisName = basisName;
  volume.coefficientsPerProbe = coefficientsPerProbe;
  volume.visibilityPerProbe = visibilityPerProbe;
  readSettings(text, volume);
  readShard(text, volume, path);
  if (volume.shard && parts == PartReading::OwnBricks) volume.rows = ProbeRows(grid, shardBricks(grid, *volume.shard));
  if (heldMasks) {
    if (!heldBricks || heldMasks->size() != heldBricks->size())
      throw InputError(fmt::format("{}: a level lists {} sub-brick masks for its bricks", path, heldMasks->size()));
    for (std::size_t n = 0; n < heldMasks->size(); ++n)
      if (((*heldMasks)[n] & subBricksInGrid(grid, (*heldBricks)[n])) == 0)
        throw InputError(fmt::format("{}: brick {} of a level holds none of its sub-bricks (mask {})", path,
                                     (*heldBricks)[n], int((*heldMasks)[n])));
    volume.rows = ProbeRows(grid, *heldBricks, *heldMasks);
    if (std::int64_t(heldBricks->size()) == grid.brickCount() && !volume.rows.holdsPartialBricks()) volume.rows = ProbeRows();
  } else if (heldBricks && std::int64_t(heldBricks->size()) < grid.brickCount()) {
    volume.rows = ProbeRows(grid, *heldBricks);
  }
  prepareForReading(volume, hasProbeStates);
  return volume;
}

std::string levelGridPrefix(int level) { return level == 0 ? "" : fmt::format("level{}/", level); }

void requireFiniteValues(const Volume& v, const std::string& path) {
  for (std::size_t i = 0; i < v.coefficients.size(); ++i)
    if (!std::isfinite(v.coefficients[i]))
      throw InputError(fmt::format("{}: probe {} has a non-finite coefficient", path,
                                   v.rows.probeAt(v.grid, std::int64_t(i / v.coefficientsPerProbe))));
  for (const auto& [values, prefix] : {std::pair{&v.skyDirect, "sky_direct"}, std::pair{&v.skyBounced, "sky_bounced"}})
    for (std::size_t i = 0; i < values->size(); ++i)
      if (!std::isfinite((*values)[i]))
        throw InputError(fmt::format("{}: probe {} has a non-finite coefficient in its {} grids", path,
                                     v.rows.probeAt(v.grid, std::int64_t(i / v.coefficientsPerProbe)), prefix));
  for (std::size_t i = 0; i < v.visibility.size(); ++i)
    if (!std::isfinite(v.visibility[i]))
      throw InputError(fmt::format("{}: probe {} has a non-finite visibility value", path,
                                   v.rows.probeAt(v.grid, std::int64_t(i / v.visibilityPerProbe))));
  const std::size_t perProbe = std::size_t(std::max(1, v.distanceMomentsPerProbe()));
  const std::size_t texels = std::size_t(v.distanceMap.texels());
  for (std::size_t i = 0; i < v.distanceMoments.size(); ++i)
    if (!(v.distanceMoments[i] >= 0.0f && v.distanceMoments[i] <= 1.0f)) {
      // Named by what it is, whichever grids the file holds it in.
      const std::size_t value = i % perProbe;
      const std::string what = value < 2 * texels ? fmt::format("texel {}'s mean{} distance", value / 2,
                                                                value % 2 ? " squared" : "")
                                                  : fmt::format("texel {}'s sky share", value - 2 * texels);
      throw InputError(fmt::format("{}: probe {} has a distance-map value ({}) of {}, outside [0, 1]", path,
                                   v.rows.probeAt(v.grid, std::int64_t(i / perProbe)), what, v.distanceMoments[i]));
    }
  for (const Eigen::Vector3f& o : v.offsets)
    if (!o.allFinite()) throw InputError(fmt::format("{}: a probe offset is not finite", path));
}

std::unique_ptr<Basis> basisInFile(const std::string& name, const std::map<std::string, std::string>& settings,
                                   const std::string& where) {
  const auto placed = [&](const std::string& message) {
    return InputError(where.empty() ? message : fmt::format("{}: {}", where, message));
  };
  try {
    return makeBasis(name, parametersFromSettings(settings));
  } catch (const SettingError& e) {
    throw placed(e.setting() == "basis" ? e.what() : "baker.setting." + std::string(e.what()));
  } catch (const InputError& e) {
    throw placed(e.what());
  }
}

}  // namespace baker
