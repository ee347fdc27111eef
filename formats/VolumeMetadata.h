#pragma once
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "basis/Basis.h"
#include "formats/VolumeLayout.h"
#include "volume/Volume.h"

namespace baker {

// The text metadata every volume file carries, whatever its format (keys "baker.*"): what the
// values mean and in which units, the basis, its colour space, the grid layout and the data to
// reconstruct the basis without this code (JSON), the tool version, and the bake settings under
// "baker.setting.*". The grid placement and per-probe counts are stored natively by each format.
// In a file of kind `file` (the distance map's grids differ), with the layout listing the probe
// grids when `hasProbeStates` (an adaptive volume's file has them though its coarsest level, a
// shard's share, may hold no probe).
std::vector<std::pair<std::string, std::string>> describingMetadata(const Volume& volume, const Basis& basis,
                                                                    bool hasProbeStates, VolumeFile file);

// The same as one JSON object of strings, for formats that keep their metadata in JSON (EXR
// slices and what is made from them: engines' exports, the viewer's page).
nlohmann::json describingMetadataJson(const Volume& volume, const Basis& basis);

// The metadata of an engine's export of `source`: what it stores, in the engine's basis `stored`
// (no sky visibility, no probe states), over the same grid and settings; the bake's own basis and
// its parameters are kept as settings "source_basis" and "source_<parameter>", so that a reader
// makes the stored basis without parameters that are not its own.
nlohmann::json exportedMetadataJson(const Volume& source, const Basis& sourceBasis, const Basis& stored);

// The metadata format version readers check; raised when the meaning of a key changes.
// 3: .vdb files carry a checksum of their bytes (formats/VdbChecksum.h).
constexpr int kVolumeFormatVersion = 3;
// 4: an adaptive volume's levels (baker.levels); only such files carry it, so that a reader of
// version 3 refuses them instead of reading their coarsest level as the whole volume.
// 5: a level's bricks may hold only some of their sub-bricks of 4³ (inactive voxels in a .vdb,
// `masks` in an EXR atlas), so that a reader of version 4 refuses them rather than taking the
// missing probes for held ones.
constexpr int kLevelsFormatVersion = 5;
constexpr int kFirstLevelsFormatVersion = 4;
// 6: the distance map is held as one RGB grid per texel (DistanceGrids::RgbPerTexel); only such
// files carry it, so that a reader of version 5 refuses them rather than missing the map's grids.
constexpr int kTexelGridsFormatVersion = 6;
// 7: a .vdb holds the distance map as one atlas grid (DistanceGrids::Atlas); likewise.
constexpr int kAtlasFormatVersion = 7;
constexpr int kNewestFormatVersion = kAtlasFormatVersion;
// The version of a uniform volume's file of kind `file`: 7 when its distance map is written as an
// atlas, 6 when RGB per texel, else 3.
int formatVersionOf(const Volume& volume, VolumeFile file);

// A volume with distance moments describes its map under this key (JSON): "size", "cap" (world
// units), "sharpness", "values_per_probe", and in words the encoding, the texel order and the units.
constexpr const char* kDistanceMapKey = "baker.distance_map";
// `form`: how the file holds it.
nlohmann::json distanceMapDescription(const DistanceMapLayout& layout, DistanceGrids form);
// Recovers volume.distanceMap from that key (none without it); InputError naming `path` and the
// key when its size or cap is out of range.
void readDistanceMap(const std::vector<std::pair<std::string, std::string>>& metadata, Volume& volume,
                     const std::string& path);
// How the file of `metadata` holds its distance map: Atlas or RgbPerTexel as the key's
// "texel_grids" says ("atlas" or "rgb", which readDistanceMap has checked), ScalarPerValue without
// it (files before format 6).
DistanceGrids distanceGridsInFile(const std::vector<std::pair<std::string, std::string>>& metadata);

// The sky a volume's light came from (volume/SkyRadiance.h), under this key (JSON): "width",
// "height", "radiance" (r, g, b per texel) and the layout in words.
constexpr const char* kSkyKey = "baker.sky";
nlohmann::json skyMetadata(const SkyRadiance& sky);
// Recovers volume.sky from that key (none without it); InputError naming `path` and the key when
// it is malformed, of another size, or holds a radiance that is negative or not finite.
void readSky(const std::vector<std::pair<std::string, std::string>>& metadata, Volume& volume, const std::string& path);

// A volume that keeps its directly seen sky apart (Volume::skyDirect, grids "sky_direct_*") says
// so, and what the grids mean, under this key.
constexpr const char* kSkyDirectKey = "baker.sky_direct";
// One that also keeps the sky's light off surfaces apart (Volume::skyBounced, grids
// "sky_bounced_*") says so under this key.
constexpr const char* kSkyBouncedKey = "baker.sky_bounced";
// Sets volume.keepsSkyDirect and keepsSkyBounced from those keys' presence (the second only with
// the first).
// InputError naming `path` for the second key without the first.
void readSkyDirect(const std::vector<std::pair<std::string, std::string>>& metadata, Volume& volume,
                   const std::string& path);

// Recovers volume.settings from "baker.setting.*" keys.
void readSettings(const std::vector<std::pair<std::string, std::string>>& metadata, Volume& volume);

// Recovers volume.shard from "baker.shard" ("K/N"), the key a shard's part carries beside
// "baker.shard.bricks", "baker.shard.fingerprint" (volume/Shard.h, bakeFingerprint) and a note.
// InputError naming `path` and the key when it is not a shard of at most kMaxShards.
void readShard(const std::vector<std::pair<std::string, std::string>>& metadata, Volume& volume,
               const std::string& path);

}  // namespace baker
