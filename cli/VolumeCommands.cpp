#include "cli/VolumeCommands.h"

#include <fmt/format.h>

#include <filesystem>
#include <iostream>
#include <limits>
#include <optional>
#include <nlohmann/json.hpp>

#include "cli/CommandLine.h"
#include "cli/SpecularFlags.h"
#include "common/Error.h"
#include "formats/VolumeLayout.h"
#include "formats/VolumeReader.h"
#include "formats/VolumeReconstruction.h"
#include "formats/VolumeSampler.h"
#include "volume/LeakAwareInterpolation.h"

namespace baker {
namespace {

// A file's size, or the sum over a volume's directory (an adaptive one's level directories too).
std::uintmax_t bytesOf(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_directory(path, ec)) return std::filesystem::file_size(path, ec);
  std::uintmax_t total = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(path, ec))
    if (entry.is_regular_file(ec)) total += entry.file_size(ec);
  return total;
}

// Probes of every level: a uniform volume's grid, or what the levels hold.
std::int64_t probesHeld(const AdaptiveVolume& volume) {
  std::int64_t probes = 0;
  for (const Volume& level : volume.levels) probes += level.rows.count(level.grid);
  return probes;
}

// Per level: its grid and what it holds; adds each probe's state to `counts`.
// A part's bricks and the whole bake's: its shard's run of the grid, or for an adaptive bake's
// part the bricks its levels hold out of every level's placed ones.
std::pair<std::int64_t, std::int64_t> partBricks(const AdaptiveVolume& volume, const nlohmann::json& levels) {
  const Volume& v = volume.coarsest();
  if (!volume.placement) return {std::int64_t(shardBricks(v.grid, *v.shard).size()), v.grid.brickCount()};
  std::int64_t held = 0, placed = 0;
  for (const nlohmann::json& level : levels) held += level["bricks"].get<std::int64_t>();
  for (const std::int64_t n : volume.placement->bricksPerLevel) placed += n;
  return {held, placed};
}

nlohmann::json levelsJson(const AdaptiveVolume& volume, std::int64_t (&counts)[kProbeStateCount]) {
  nlohmann::json levels = nlohmann::json::array();
  for (std::size_t k = 0; k < volume.levels.size(); ++k) {
    const Volume& level = volume.levels[k];
    for (ProbeState s : level.states) ++counts[int(s)];
    if (level.states.empty()) counts[int(ProbeState::Valid)] += level.grid.probeCount();
    const ProbeGrid& g = level.grid;
    levels.push_back({{"level", k},
                      {"dims", {g.dims.x(), g.dims.y(), g.dims.z()}},
                      {"origin", {g.origin.x(), g.origin.y(), g.origin.z()}},
                      {"spacing", g.spacing},
                      {"bricks", level.rows.holdsEveryProbe() ? g.brickCount() : std::int64_t(level.rows.bricks().size())},
                      {"probes", level.rows.count(g)}});
  }
  return levels;
}

// The specular part of sample's answer (null when not asked for); InputError when the volume
// holds irradiance.
nlohmann::json specularJson(const std::optional<SpecularRequest>& request, const VolumeReconstruction& reading,
                            const std::string& path, const float* coefficients, const Eigen::Vector3d& normal) {
  if (!request) return nullptr;
  if (reading.signal() != StoredSignal::Radiance)
    throw InputError(fmt::format("{}: holds irradiance (setting signal), from which no specular can be read; bake "
                                 "with --signal radiance",
                                 path));
  const Eigen::Vector3d& view = request->view;
  const VolumeReconstruction::Specular s = reading.specular(coefficients, normal, view, request->roughness);
  return {{"roughness", request->roughness},
          {"view", {view.x(), view.y(), view.z()}},
          {"value", {s.value.x(), s.value.y(), s.value.z()}},
          {"albedo", s.albedo},
          {"diffuse_weight", s.diffuseWeight}};
}

// Per probe held around the position: where it is in the grid, its trilinear weight and its leak factor.
nlohmann::json probeWeightsJson(const ProbeInterpolation& interpolation, const LeakAwareCorner* corners) {
  nlohmann::json weights = nlohmann::json::array();
  for (int n = 0; n < interpolation.corners; ++n)
    if (interpolation.held[n] >= 0)
      weights.push_back({{"probe", {corners[n].probe.x(), corners[n].probe.y(), corners[n].probe.z()}},
                         {"trilinear", corners[n].trilinear},
                         {"leak", corners[n].leak}});
  return weights;
}

}  // namespace

int runSampleCommand(int argc, char** argv) {
  CLI::App app{"Irradiance and sky visibility of a volume at a world position, for a normal."};
  std::string path, at, normalText;
  bool json = false;
  app.add_option("volume", path, "volume: .vdb, or a directory of EXR slices, a Bevy or a three.js export")->required();
  app.add_option("--at", at, "world position x,y,z")->required();
  app.add_option("--normal", normalText, "surface normal x,y,z (normalised here)")->required();
  SpecularFlags specularFlags;
  specularFlags.addTo(app);
  bool leakAware = false;
  app.add_flag("--leak-aware", leakAware,
               "weigh the eight probes by what their distance maps say: a probe whose map sees a wall between it and "
               "the position, or its surface, counts for little (Chebyshev test and back-face weight, "
               "docs/LEAKS.md); trilinear where no map sees a surface");
  app.add_flag("--json", json, "print the result as JSON on stdout");
  return runGuarded("baker sample", app, argc, argv, [&]() {
    const Eigen::Vector3d position = parseTriple("--at", at);
    const Eigen::Vector3d normal = parseDirection("--normal", normalText);
    const std::optional<SpecularRequest> specular = specularRequest(specularFlags);
    const AdaptiveVolume levels = readLevels(path);
    const VolumeReconstruction reading(levels.coarsest());
    if (leakAware && levels.coarsest().distanceMomentsPerProbe() == 0)
      throw InputError(fmt::format("{}: holds no distance moments, which --leak-aware reads (bake it again with "
                                   "--placement uniform and --distance-map above 0)",
                                   path));
    const SurfaceReading s = sampleOnSurface(levels, position, normal, leakAware, path);
    const Volume& volume = levels.levels[std::size_t(s.level)];
    const Eigen::Vector3f e = reading.irradiance(s.coefficients.data(), normal);
    const bool hasVisibility = volume.visibilityPerProbe > 0;
    const double sky = hasVisibility ? reading.skyVisibility(s.visibility.data(), normal) : 0.0;
    const nlohmann::json glossy = specularJson(specular, reading, path, s.coefficients.data(), normal);
    if (json) {
      nlohmann::json j = {{"volume", path},
                          {"basis", reading.basis().name()},
                          {"signal", storedSignalName(reading.signal())},
                          {"position", {position.x(), position.y(), position.z()}},
                          {"normal", {normal.x(), normal.y(), normal.z()}},
                          {"grid_position", {s.gridPosition.x(), s.gridPosition.y(), s.gridPosition.z()}},
                          {"level", s.level},
                          {"level_spacing", volume.grid.spacing},
                          {"irradiance", {e.x(), e.y(), e.z()}},
                          {"coefficients", s.coefficients}};
      j["sky_visibility"] = hasVisibility ? nlohmann::json(sky) : nlohmann::json(nullptr);
      j["specular"] = glossy;
      j["leak_aware"] = leakAware;
      if (leakAware) j["probe_weights"] = probeWeightsJson(s.interpolation, s.corners);
      std::cout << j.dump(2) << "\n";
    } else {
      std::cout << fmt::format("irradiance E = ({:.6g}, {:.6g}, {:.6g}) at ({}, {}, {}) for normal ({:.4f}, {:.4f}, "
                               "{:.4f}); probe coordinates ({:.3f}, {:.3f}, {:.3f})\n",
                               e.x(), e.y(), e.z(), position.x(), position.y(), position.z(), normal.x(), normal.y(),
                               normal.z(), s.gridPosition.x(), s.gridPosition.y(), s.gridPosition.z());
      if (levels.levels.size() > 1)
        std::cout << fmt::format("level {} of {} (spacing {:.4g} m)\n", s.level, levels.levels.size(),
                                 volume.grid.spacing);
      if (hasVisibility) std::cout << fmt::format("sky visibility {:.4f}\n", sky);
      if (!glossy.is_null())
        std::cout << fmt::format("specular S = ({:.6g}) at roughness {} (GGX mean radiance; albedo {:.4f}, diffuse "
                                 "weight {:.4f})\n",
                                 fmt::join(glossy["value"].get<std::vector<double>>(), ", "), specular->roughness,
                                 glossy["albedo"].get<double>(), glossy["diffuse_weight"].get<double>());
    }
    return 0;
  });
}

namespace {

// Each grid with its smallest and largest value over every level, named as the file holds them
// (`distanceGrids`: a file of format 3 keeps a scalar grid per distance-map value).
nlohmann::json gridRanges(const AdaptiveVolume& volume, const Basis& basis, DistanceGrids distanceGrids) {
  const Volume& v = volume.coarsest();
  nlohmann::json grids = nlohmann::json::array();
  for (const VolumeGrid& grid : volumeGrids(basis, v.visibilityPerProbe, v.hasProbeStates(), v.distanceMap,
                                            distanceGrids, v.keepsSkyDirect, v.keepsSkyBounced)) {
    float lo = std::numeric_limits<float>::infinity(), hi = -lo;
    for (const Volume& level : volume.levels)
      for (std::int64_t row = 0; row < level.rows.count(level.grid); ++row) {
        const std::int64_t probe = level.rows.probeAt(level.grid, row);
        for (const VolumeGrid& held : perProbeGridsOf(grid, v.distanceMap))
          for (int c = 0; c < held.components; ++c) {
            const float value = gridValue(level, held, c, probe);
            lo = std::min(lo, value);
            hi = std::max(hi, value);
          }
      }
    grids.push_back({{"name", grid.name}, {"components", grid.components}, {"min", lo}, {"max", hi}});
  }
  return grids;
}

}  // namespace

int runInspectCommand(int argc, char** argv) {
  CLI::App app{"Describe what a volume holds."};
  std::string path;
  bool json = false;
  app.add_option("volume", path, "volume: .vdb, or a directory of EXR slices, a Bevy or a three.js export")->required();
  app.add_flag("--json", json, "print the description as JSON on stdout");
  return runGuarded("baker inspect", app, argc, argv, [&]() {
    const AdaptiveVolume volume = readLevels(path);
    const Volume& v = volume.coarsest();
    const std::unique_ptr<Basis> basis = basisOf(v);
    const ProbeGrid& g = v.grid;
    const nlohmann::json grids = gridRanges(volume, *basis, distanceGridsOf(path));
    std::int64_t counts[kProbeStateCount] = {};
    const nlohmann::json levels = levelsJson(volume, counts);
    const std::uintmax_t bytes = bytesOf(path);
    if (json) {
      const nlohmann::json j = {
          {"volume", path},
          {"format", volumeFormatOf(path)},
          {"bytes", bytes},
          {"basis", v.basisName},
          {"signal", storedSignalName(storedSignalOf(v.settings))},
          {"dims", {g.dims.x(), g.dims.y(), g.dims.z()}},
          {"origin", {g.origin.x(), g.origin.y(), g.origin.z()}},
          {"spacing", g.spacing},
          {"probes", probesHeld(volume)},
          {"coefficients_per_probe", v.coefficientsPerProbe},
          {"visibility_per_probe", v.visibilityPerProbe},
          {"probe_states", {{"valid", counts[1]}, {"relocated", counts[2]}, {"invalid", counts[0]},
                            {"interpolated", counts[3]}}},
          {"levels", levels},
          {"margin_cells", volume.levels.size() > 1 ? nlohmann::json(volume.marginCells) : nlohmann::json(nullptr)},
          {"grids", grids},
          {"settings", v.settings},
          {"shard", v.shard ? nlohmann::json{{"index", v.shard->index}, {"count", v.shard->count},
                                             {"bricks", partBricks(volume, levels).first}}
                            : nlohmann::json(nullptr)}};
      std::cout << j.dump(2) << "\n";
      return 0;
    }
    std::cout << fmt::format("{}: {} bytes, basis {} ({}), {} × {} × {} probes ({}), spacing {:.6g}, origin ({:.6g}, "
                             "{:.6g}, {:.6g})\n",
                             path, bytes, v.basisName, storedSignalName(storedSignalOf(v.settings)), g.dims.x(), g.dims.y(), g.dims.z(), g.probeCount(), g.spacing,
                             g.origin.x(), g.origin.y(), g.origin.z());
    if (v.shard)
      std::cout << fmt::format("part: shard {} of a bake ({} of {} bricks); probes outside it count as invalid here, "
                               "and invalid probes are filled when the parts are merged (baker merge)\n",
                               shardName(*v.shard), partBricks(volume, levels).first, partBricks(volume, levels).second);
    if (volume.levels.size() > 1) {
      std::cout << fmt::format("adaptive: {} levels, spacing ×{} per level, probes traced within {} cell(s) of geometry\n",
                               volume.levels.size(), kLevelRatio, volume.marginCells);
      for (const nlohmann::json& level : levels)
        std::cout << fmt::format("  level {}: spacing {:.6g}, {} bricks, {} probes\n", level["level"].get<int>(),
                                 level["spacing"].get<double>(), level["bricks"].get<std::int64_t>(),
                                 level["probes"].get<std::int64_t>());
    }
    std::cout << fmt::format("probes: {} valid, {} relocated, {} invalid{}{}\n", counts[1], counts[2], counts[0],
                             v.shard ? "" : " (filled from neighbours)",
                             counts[3] > 0 ? fmt::format(", {} interpolated from the coarser level", counts[3]) : "");
    for (const nlohmann::json& grid : grids)
      std::cout << fmt::format("  {:<16} {}  [{:.6g}, {:.6g}]\n", grid["name"].get<std::string>(),
                               grid["components"].get<int>() == 3 ? "vec3 " : "float", grid["min"].get<float>(),
                               grid["max"].get<float>());
    for (const auto& [key, value] : v.settings) std::cout << fmt::format("  setting {} = {}\n", key, value);
    return 0;
  });
}

}  // namespace baker
