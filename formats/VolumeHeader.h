#pragma once
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "basis/Basis.h"
#include "volume/ProbeGrid.h"
#include "volume/Volume.h"

namespace baker {

// Far beyond any bake (--spacing refuses grids above 2^27 probes) and small enough that a
// corrupted size is refused before it allocates.
constexpr double kMaxProbesRead = double(1 << 28);

// How much of a shard's part a reader holds: every probe of the grid (zeros outside the part's
// bricks, as other commands expect), or only the part's own bricks (ProbeRows), as the merge
// reads parts so that it holds the whole volume and one shard's share, not two whole volumes.
// A voxel outside the part's bricks is refused when reading its own bricks only.
enum class PartReading { EveryProbe, OwnBricks };

// The key an adaptive volume's file gives its number of levels; a file without it has one.
constexpr const char* kLevelsKey = "baker.levels";
// A shard's part of an adaptive bake records the whole bake's placement (PlacementSummary): the
// hash over every level's placed bricks, and their count per level ("n0,n1,…").
constexpr const char* kPlacementKey = "baker.shard.placement";
constexpr const char* kPlacedBricksKey = "baker.shard.placed_bricks";
// "" for level 0, whose grids are named as a uniform volume's; "levelK/" for a finer level K.
std::string levelGridPrefix(int level);

// What a reader learns from a file before its values: checked once, the same for every format.
struct VolumeHeader {
  std::string basisName;
  ProbeGrid grid;
  int coefficientsPerProbe = 0;
  int visibilityPerProbe = 0;
  bool hasProbeStates = false;
  std::vector<std::pair<std::string, std::string>> text;  // every "baker.*" key as text
  // A level of an adaptive volume holds only these bricks (Volume::rows); none: every probe.
  std::optional<std::vector<std::int64_t>> heldBricks;
  // Per held brick, its sub-bricks held (volume/SubBricks.h); none: every one.
  std::optional<std::vector<std::uint8_t>> heldMasks;

  // Checks the header against the basis it names and the limits (InputError naming `path` and
  // the key), then returns a volume with zeroed arrays of the right sizes and the settings.
  Volume emptyVolume(const std::string& path, PartReading parts = PartReading::EveryProbe) const;
};

// InputError naming `path` and the probe when a value read from a file is NaN or infinite.
void requireFiniteValues(const Volume& volume, const std::string& path);

// The basis a file names with the parameters its settings record, or InputError naming `where`
// (the file; may be empty) and the setting: a file's basis is what the file says, not a setting
// of the command reading it.
std::unique_ptr<Basis> basisInFile(const std::string& name, const std::map<std::string, std::string>& settings,
                                   const std::string& where);

}  // namespace baker
