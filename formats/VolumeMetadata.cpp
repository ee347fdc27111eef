#include "formats/VolumeMetadata.h"

#include <fmt/format.h>

#include <algorithm>
#include <nlohmann/json.hpp>

#include "basis/SpecularBlend.h"
#include "basis/StoredSignal.h"
#include "common/Error.h"

#include "formats/ReconstructionData.h"
#include "formats/VolumeLayout.h"

namespace baker {
namespace {

constexpr const char* kOctahedralEncoding =
    "octahedral, +Y up: p = (d.x, d.z) / (|d.x| + |d.y| + |d.z|), for d.y < 0 folded to ((1 - |p.y|) sign p.x, "
    "(1 - |p.x|) sign p.y) with sign 0 = +1; (u, v) = (p + 1) / 2; texel (i, j) covers [i, i + 1) / size in u and "
    "[j, j + 1) / size in v";

const char* kindName(VolumeGrid::Kind kind) {
  switch (kind) {
    case VolumeGrid::Kind::Coefficients: return "irradiance_coefficients";
    case VolumeGrid::Kind::SkyDirect: return "sky_direct_coefficients";
    case VolumeGrid::Kind::SkyBounced: return "sky_bounced_coefficients";
    case VolumeGrid::Kind::Visibility: return "sky_visibility_coefficients";
    case VolumeGrid::Kind::DistanceAtlas: return "distance_atlas";
    case VolumeGrid::Kind::DistanceMap: return "distance_map";
    case VolumeGrid::Kind::DistanceMoments: return "distance_moments";
    case VolumeGrid::Kind::SkyVisibilityMap: return "sky_visibility_map";
    case VolumeGrid::Kind::ProbeState: return "probe_state";
    case VolumeGrid::Kind::ProbeOffset: return "probe_offset";
  }
  return "";
}

}  // namespace

std::vector<std::pair<std::string, std::string>> describingMetadata(const Volume& volume, const Basis& basis,
                                                                    bool hasProbeStates, VolumeFile file) {
  const DistanceGrids distanceGrids = distanceGridsWritten(volume.distanceMap, file);
  nlohmann::json layout = nlohmann::json::array();
  for (const VolumeGrid& g : volumeGrids(basis, volume.visibilityPerProbe, hasProbeStates, volume.distanceMap,
                                         distanceGrids, volume.keepsSkyDirect, volume.keepsSkyBounced)) {
    nlohmann::json entry = {{"name", g.name}, {"kind", kindName(g.kind)}, {"components", g.components}};
    if (g.kind == VolumeGrid::Kind::Coefficients || g.kind == VolumeGrid::Kind::SkyDirect ||
        g.kind == VolumeGrid::Kind::SkyBounced || g.kind == VolumeGrid::Kind::Visibility ||
        g.kind == VolumeGrid::Kind::DistanceMap || g.kind == VolumeGrid::Kind::DistanceMoments ||
        g.kind == VolumeGrid::Kind::SkyVisibilityMap)
      entry["index"] = std::vector<int>(g.index, g.index + g.components);
    layout.push_back(entry);
  }
  const StoredSignal signal = storedSignalOf(volume.settings);
  const bool radiance = signal == StoredSignal::Radiance;
  std::vector<std::pair<std::string, std::string>> meta = {
      {"baker.version", BAKER_VERSION},
      {"baker.format_version", std::to_string(formatVersionOf(volume, file))},
      {"baker.basis", basis.name()},
      {"baker.quantity", storedSignalName(signal)},
      {"baker.units", radiance ? "coefficients of the incoming radiance L(w) in the scene's radiance units; irradiance "
                                 "E(n) = sum of c_i K_i(n), K_i(n) = integral of f_i(w) max(0, n.w) dw (docs/DECODERS.md)"
                               : "coefficients of E(n) = integral of L(w) max(0, n.w) dw: full irradiance (not E/pi) in "
                                 "the scene's radiance units times steradians; glTF numbers used as they are"},
      {"baker.visibility",
       radiance ? "coefficients, in channel 0's functions, of V(w) = 1 where a ray escapes the scene, 0 where it hits "
                  "geometry; (1/pi) sum of v_i K_i(n) is the cosine-weighted sky visibility"
                : "coefficients, in channel 0's functions, of V(n) = (1/pi) integral of V(w) max(0, n.w) dw, V(w) = 1 "
                  "where a ray escapes the scene: 1 under open sky"},
      {"baker.color_space", colorSpaceName(basis.colorSpace())},
      {"baker.layout", layout.dump()},
      {"baker.reconstruction", reconstructionData(basis, signal).dump()},
  };
  // How glossy specular is read from radiance, for decoders to read it the same way.
  if (radiance) meta.push_back({"baker.specular", specularBlendOf(basis)->describe().dump()});
  if (volume.distanceMomentsPerProbe() > 0)
    meta.push_back({kDistanceMapKey, distanceMapDescription(volume.distanceMap, distanceGrids).dump()});
  if (volume.sky) meta.push_back({kSkyKey, skyMetadata(*volume.sky).dump()});
  if (volume.keepsSkyDirect)
    meta.push_back({kSkyDirectKey,
                    "grids sky_direct_*: the part of the coefficients (same functions, channels and units) that is "
                    "the sky seen directly from the probe, along the rays that escaped and the sky's importance "
                    "samples; coefficients minus sky_direct is the light that does not come straight from the sky "
                    "(lamps, emission, and the sky's light off surfaces), which stays when the sky is swapped"});
  if (volume.keepsSkyBounced)
    meta.push_back({kSkyBouncedKey,
                    "grids sky_bounced_*: the part of the coefficients (same functions, channels and units) that is "
                    "the sky's light off surfaces, the paths that reflected before the sky lit them; coefficients "
                    "minus sky_direct minus sky_bounced is the light of lamps and emission alone"});
  for (const auto& [key, value] : volume.settings) meta.push_back({"baker.setting." + key, value});
  if (volume.shard) {
    meta.push_back({"baker.shard", shardName(*volume.shard)});
    meta.push_back({"baker.shard.bricks", std::to_string(shardBricks(volume.grid, *volume.shard).size())});
    meta.push_back({"baker.shard.fingerprint", bakeFingerprint(volume.basisName, volume.grid, volume.settings)});
    meta.push_back({"baker.shard.note",
                    "one part of a bake cut into shards: only the shard's bricks are stored, and its invalid probes "
                    "are filled from their neighbours when the parts are merged"});
  }
  return meta;
}

nlohmann::json describingMetadataJson(const Volume& volume, const Basis& basis) {
  nlohmann::json metadata = nlohmann::json::object();
  for (const auto& [key, value] : describingMetadata(volume, basis, volume.hasProbeStates(), VolumeFile::ExrSlices))
    metadata[key] = value;
  return metadata;
}

nlohmann::json exportedMetadataJson(const Volume& source, const Basis& sourceBasis, const Basis& stored) {
  Volume held;
  held.grid = source.grid;
  held.basisName = stored.name();
  held.coefficientsPerProbe = stored.totalCoefficients();
  held.settings = source.settings;
  held.settings["source_basis"] = sourceBasis.name();
  // An engine's format holds irradiance, as baker reads it back, whatever the bake stored.
  held.settings["source_signal"] = storedSignalName(storedSignalOf(source.settings));
  held.settings["signal"] = storedSignalName(StoredSignal::Irradiance);
  for (const auto& [name, value] : parameterSettings(sourceBasis.parameters())) {
    held.settings.erase(name);
    held.settings["source_" + name] = value;
  }
  return describingMetadataJson(held, stored);
}

void readSettings(const std::vector<std::pair<std::string, std::string>>& metadata, Volume& volume) {
  const std::string prefix = "baker.setting.";
  for (const auto& [key, value] : metadata)
    if (key.rfind(prefix, 0) == 0) volume.settings[key.substr(prefix.size())] = value;
}

void readShard(const std::vector<std::pair<std::string, std::string>>& metadata, Volume& volume,
               const std::string& path) {
  const auto entry = std::find_if(metadata.begin(), metadata.end(), [](const auto& e) { return e.first == "baker.shard"; });
  if (entry == metadata.end()) return;
  volume.shard = parseShard(entry->second);
  if (!volume.shard)
    throw InputError(fmt::format("{}: baker.shard \"{}\" is not K/N with 0 <= K < N <= {}", path, entry->second,
                                 kMaxShards));
}

int formatVersionOf(const Volume& volume, VolumeFile file) {
  if (volume.distanceMomentsPerProbe() == 0) return kVolumeFormatVersion;
  switch (distanceGridsWritten(volume.distanceMap, file)) {
    case DistanceGrids::Atlas: return kAtlasFormatVersion;
    case DistanceGrids::RgbPerTexel: return kTexelGridsFormatVersion;
    case DistanceGrids::ScalarPerValue: break;
  }
  return kVolumeFormatVersion;
}

nlohmann::json distanceMapDescription(const DistanceMapLayout& layout, DistanceGrids form) {
  nlohmann::json map = {{"size", layout.size},
                        {"cap", layout.cap},
                        {"sharpness", layout.sharpness()},
                        {"values_per_probe", layout.valuesPerProbe()},
                        {"encoding", kOctahedralEncoding},
                        {"sky_visibility", layout.skyVisibility},
                        {"invalid_probes", "probes inside geometry hold zeros: leak-aware readers turn them away"}};
  // What a texel's R, G and B hold, in either RGB form.
  const std::string texel =
      ": R the mean distance to the first surface, G the mean squared distance, in units of cap and cap^2 (rays that "
      "escape, and distances beyond the cap, count as the cap), B the share of the rays that escaped to the sky, in "
      "[0, 1]; each ray w weighs max(0, c.w)^sharpness in the texel of direction c";
  if (form == DistanceGrids::Atlas) {
    map["texel_grids"] = "atlas";
    map["values"] = "distance_map holds texel t = u + size * v of probe (i, j, k) at voxel (i * size + u, j * size + v, "
                    "k), its transform's voxels size times smaller than the probe spacing in x and y" + texel;
    return map;
  }
  if (form == DistanceGrids::RgbPerTexel) {
    map["texel_grids"] = "rgb";
    map["values"] = "distance_map_NNN holds texel t = NNN = i + size * j" + texel;
    return map;
  }
  map["values"] =
      "distance_moments_NNN: value 2t is the mean distance to the first surface, 2t + 1 the mean squared distance, of "
      "texel t = i + size * j, in units of cap and cap^2; rays that escape, and distances beyond the cap, count as the "
      "cap; each ray w weighs max(0, c.w)^sharpness in the texel of direction c";
  map["sky_visibility_values"] =
      "with sky_visibility: sky_visibility_map_NNN, value 2 * size * size + t of the probe, is the share of texel t's "
      "rays (weighted as the moments) that escaped to the sky, in [0, 1]";
  return map;
}

namespace {

// The value of `key`, or null when the metadata has none.
const std::string* metadataValue(const std::vector<std::pair<std::string, std::string>>& metadata,
                                 const std::string& key) {
  const auto entry = std::find_if(metadata.begin(), metadata.end(), [&](const auto& e) { return e.first == key; });
  return entry == metadata.end() ? nullptr : &entry->second;
}

}  // namespace

void readDistanceMap(const std::vector<std::pair<std::string, std::string>>& metadata, Volume& volume,
                     const std::string& path) {
  const std::string* value = metadataValue(metadata, kDistanceMapKey);
  if (!value) return;
  DistanceMapLayout layout;
  try {
    const nlohmann::json map = nlohmann::json::parse(*value);
    layout.size = map.at("size").get<int>();
    layout.cap = map.at("cap").get<double>();
    layout.skyVisibility = map.value("sky_visibility", false);
    if (map.contains("texel_grids") &&
        !((map["texel_grids"] == "rgb" || map["texel_grids"] == "atlas") && layout.skyVisibility))
      throw InputError(fmt::format("{}: {} \"texel_grids\" is {}; this reader knows \"rgb\" and \"atlas\", with "
                                   "\"sky_visibility\" true", path, kDistanceMapKey, map["texel_grids"].dump()));
  } catch (const nlohmann::json::exception& e) {
    throw InputError(fmt::format("{}: {} is not a distance map's description: {}", path, kDistanceMapKey, oneLine(e.what())));
  }
  if (layout.size < 2 || layout.size > 64)
    throw InputError(fmt::format("{}: {} \"size\" is {}; a distance map has 2 to 64 texels per side", path,
                                 kDistanceMapKey, layout.size));
  if (!(layout.cap > 0.0) || !std::isfinite(layout.cap * layout.cap))
    throw InputError(fmt::format("{}: {} \"cap\" must be a positive distance whose square is finite", path,
                                 kDistanceMapKey));
  volume.distanceMap = layout;
}

DistanceGrids distanceGridsInFile(const std::vector<std::pair<std::string, std::string>>& metadata) {
  const std::string* value = metadataValue(metadata, kDistanceMapKey);
  if (!value) return DistanceGrids::ScalarPerValue;
  // readDistanceMap refuses any value but "rgb" and "atlas".
  const nlohmann::json map = nlohmann::json::parse(*value, nullptr, /*allow_exceptions=*/false);
  if (!map.is_object() || !map.contains("texel_grids")) return DistanceGrids::ScalarPerValue;
  return map["texel_grids"] == "atlas" ? DistanceGrids::Atlas : DistanceGrids::RgbPerTexel;
}

nlohmann::json skyMetadata(const SkyRadiance& sky) {
  return {{"width", sky.width},
          {"height", sky.height},
          {"radiance", sky.rgb},
          {"layout",
           "lat-long of world directions, +Y up: texel (i, j), row 0 at the top, covers u in [i, i + 1) / width and v "
           "in [j, j + 1) / height, phi = 2 pi (u - 1/2), theta = pi v, d = (sin theta cos phi, cos theta, sin theta "
           "sin phi); radiance holds r, g, b of each texel, row by row from the top: its mean radiance (flux / solid "
           "angle)"},
          {"meaning",
           "the sky the volume's light came from (setting sky): relighting takes it away through each probe's "
           "visibility before adding another (docs/RELIGHTING.md)"}};
}

void readSkyDirect(const std::vector<std::pair<std::string, std::string>>& metadata, Volume& volume,
                   const std::string& path) {
  volume.keepsSkyDirect = metadataValue(metadata, kSkyDirectKey) != nullptr;
  volume.keepsSkyBounced = metadataValue(metadata, kSkyBouncedKey) != nullptr;
  if (volume.keepsSkyBounced && !volume.keepsSkyDirect)
    throw InputError(fmt::format("{}: has {} without {}: the sky's light off surfaces is kept only beside the sky "
                                 "seen directly",
                                 path, kSkyBouncedKey, kSkyDirectKey));
}

void readSky(const std::vector<std::pair<std::string, std::string>>& metadata, Volume& volume, const std::string& path) {
  const std::string* value = metadataValue(metadata, kSkyKey);
  if (!value) return;
  SkyRadiance sky;
  try {
    const nlohmann::json j = nlohmann::json::parse(*value);
    sky.width = j.at("width").get<int>();
    sky.height = j.at("height").get<int>();
    if (sky.width != SkyRadiance::kWidth || sky.height != SkyRadiance::kHeight)
      throw InputError(fmt::format("{}: {} is {} x {} texels; this version reads {} x {}", path, kSkyKey, sky.width,
                                   sky.height, SkyRadiance::kWidth, SkyRadiance::kHeight));
    const nlohmann::json& values = j.at("radiance");
    if (!values.is_array() || values.size() != sky.rgb.size())
      throw InputError(fmt::format("{}: {} \"radiance\" must hold {} numbers (r, g, b per texel)", path, kSkyKey,
                                   sky.rgb.size()));
    for (std::size_t i = 0; i < sky.rgb.size(); ++i) sky.rgb[i] = values[i].get<float>();
  } catch (const nlohmann::json::exception& e) {
    throw InputError(fmt::format("{}: {} is not a sky's description: {}", path, kSkyKey, oneLine(e.what())));
  }
  for (const float value : sky.rgb)
    if (!(std::isfinite(value) && value >= 0.0f))
      throw InputError(fmt::format("{}: {} \"radiance\" holds {}; radiance is finite and not negative", path,
                                   kSkyKey, value));
  volume.sky = std::move(sky);
}

}  // namespace baker
