#include "cli/VolumeCommands.h"

#include <fmt/format.h>

#include <filesystem>
#include <iostream>
#include <limits>
#include <nlohmann/json.hpp>

#include "cli/CommandLine.h"
#include "common/Error.h"
#include "formats/VolumeLayout.h"
#include "formats/VolumeReader.h"
#include "formats/VolumeSampler.h"

namespace baker {
namespace {

std::uintmax_t bytesOf(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_directory(path, ec)) return std::filesystem::file_size(path, ec);
  std::uintmax_t total = 0;
  for (const auto& entry : std::filesystem::directory_iterator(path, ec))
    if (entry.is_regular_file(ec)) total += entry.file_size(ec);
  return total;
}

}  // namespace

int runSampleCommand(int argc, char** argv) {
  CLI::App app{"Irradiance and sky visibility of a volume at a world position, for a normal."};
  std::string path, at, normalText;
  bool json = false;
  app.add_option("volume", path, "volume: .vdb, or a directory of EXR slices, a Bevy or a three.js export")->required();
  app.add_option("--at", at, "world position x,y,z")->required();
  app.add_option("--normal", normalText, "surface normal x,y,z (normalised here)")->required();
  app.add_flag("--json", json, "print the result as JSON on stdout");
  return runGuarded("baker sample", app, argc, argv, [&]() {
    const Eigen::Vector3d position = parseTriple("--at", at);
    Eigen::Vector3d normal = parseTriple("--normal", normalText);
    if (!(normal.norm() > 0.0)) throw InputError("--normal must not be zero");
    normal.normalize();
    const Volume volume = readVolume(path);
    const std::unique_ptr<Basis> basis = basisOf(volume);
    const VolumeSample s = sampleVolume(volume, position);
    const Eigen::Vector3f e = basis->reconstruct(s.coefficients.data(), normal);
    const bool hasVisibility = volume.visibilityPerProbe > 0;
    const double sky = hasVisibility ? reconstructVisibility(*basis, s.visibility.data(), normal) : 0.0;
    if (json) {
      nlohmann::json j = {{"volume", path},
                          {"basis", basis->name()},
                          {"position", {position.x(), position.y(), position.z()}},
                          {"normal", {normal.x(), normal.y(), normal.z()}},
                          {"grid_position", {s.gridPosition.x(), s.gridPosition.y(), s.gridPosition.z()}},
                          {"irradiance", {e.x(), e.y(), e.z()}},
                          {"coefficients", s.coefficients}};
      j["sky_visibility"] = hasVisibility ? nlohmann::json(sky) : nlohmann::json(nullptr);
      std::cout << j.dump(2) << "\n";
    } else {
      std::cout << fmt::format("irradiance E = ({:.6g}, {:.6g}, {:.6g}) at ({}, {}, {}) for normal ({:.4f}, {:.4f}, "
                               "{:.4f}); probe coordinates ({:.3f}, {:.3f}, {:.3f})\n",
                               e.x(), e.y(), e.z(), position.x(), position.y(), position.z(), normal.x(), normal.y(),
                               normal.z(), s.gridPosition.x(), s.gridPosition.y(), s.gridPosition.z());
      if (hasVisibility) std::cout << fmt::format("sky visibility {:.4f}\n", sky);
    }
    return 0;
  });
}

int runInspectCommand(int argc, char** argv) {
  CLI::App app{"Describe what a volume holds."};
  std::string path;
  bool json = false;
  app.add_option("volume", path, "volume: .vdb, or a directory of EXR slices, a Bevy or a three.js export")->required();
  app.add_flag("--json", json, "print the description as JSON on stdout");
  return runGuarded("baker inspect", app, argc, argv, [&]() {
    const Volume v = readVolume(path);
    const std::unique_ptr<Basis> basis = basisOf(v);
    const ProbeGrid& g = v.grid;
    nlohmann::json grids = nlohmann::json::array();
    for (const VolumeGrid& grid : volumeGrids(*basis, v.visibilityPerProbe, !v.states.empty())) {
      float lo = std::numeric_limits<float>::infinity(), hi = -lo;
      for (std::int64_t p = 0; p < g.probeCount(); ++p)
        for (int c = 0; c < grid.components; ++c) {
          const float value = gridValue(v, grid, c, p);
          lo = std::min(lo, value);
          hi = std::max(hi, value);
        }
      grids.push_back({{"name", grid.name}, {"components", grid.components}, {"min", lo}, {"max", hi}});
    }
    std::int64_t counts[3] = {0, 0, 0};
    for (ProbeState s : v.states) ++counts[int(s)];
    if (v.states.empty()) counts[int(ProbeState::Valid)] = g.probeCount();
    const std::uintmax_t bytes = bytesOf(path);
    if (json) {
      const nlohmann::json j = {
          {"volume", path},
          {"format", volumeFormatOf(path)},
          {"bytes", bytes},
          {"basis", v.basisName},
          {"dims", {g.dims.x(), g.dims.y(), g.dims.z()}},
          {"origin", {g.origin.x(), g.origin.y(), g.origin.z()}},
          {"spacing", g.spacing},
          {"probes", g.probeCount()},
          {"coefficients_per_probe", v.coefficientsPerProbe},
          {"visibility_per_probe", v.visibilityPerProbe},
          {"probe_states", {{"valid", counts[1]}, {"relocated", counts[2]}, {"invalid", counts[0]}}},
          {"grids", grids},
          {"settings", v.settings},
          {"shard", v.shard ? nlohmann::json{{"index", v.shard->index}, {"count", v.shard->count},
                                             {"bricks", shardBricks(g, *v.shard).size()}}
                            : nlohmann::json(nullptr)}};
      std::cout << j.dump(2) << "\n";
      return 0;
    }
    std::cout << fmt::format("{}: {} bytes, basis {}, {} × {} × {} probes ({}), spacing {:.6g}, origin ({:.6g}, {:.6g}, {:.6g})\n",
                             path, bytes, v.basisName, g.dims.x(), g.dims.y(), g.dims.z(), g.probeCount(), g.spacing,
                             g.origin.x(), g.origin.y(), g.origin.z());
    if (v.shard)
      std::cout << fmt::format("part: shard {} of a bake ({} of {} bricks); probes outside it count as invalid here, "
                               "and invalid probes are filled when the parts are merged (baker merge)\n",
                               shardName(*v.shard), shardBricks(g, *v.shard).size(), g.brickCount());
    std::cout << fmt::format("probes: {} valid, {} relocated, {} invalid{}\n", counts[1], counts[2], counts[0],
                             v.shard ? "" : " (filled from neighbours)");
    for (const nlohmann::json& grid : grids)
      std::cout << fmt::format("  {:<16} {}  [{:.6g}, {:.6g}]\n", grid["name"].get<std::string>(),
                               grid["components"].get<int>() == 3 ? "vec3 " : "float", grid["min"].get<float>(),
                               grid["max"].get<float>());
    for (const auto& [key, value] : v.settings) std::cout << fmt::format("  setting {} = {}\n", key, value);
    return 0;
  });
}

}  // namespace baker
