#include "formats/ExrLevels.h"

#include <fmt/format.h>

#include <filesystem>

#include "common/Error.h"
#include "formats/AtomicFile.h"
#include "formats/LevelChecks.h"
#include "formats/VolumeHeader.h"
#include "formats/VolumeMetadata.h"
#include "volume/LevelGrids.h"
#include "volume/StoredBricks.h"

namespace baker {
namespace {

constexpr const char* kLevelRatioKey = "level_ratio";
constexpr const char* kMarginKey = "margin_cells";

std::string levelDirectory(int level) { return fmt::format("level{}", level); }

// What the root manifest says of the levels.
struct LevelsManifest {
  std::vector<std::string> directories;
  int marginCells = 0;
  std::string basis;
};

LevelsManifest levelsManifest(const nlohmann::json& m, const std::string& manifestPath) {
  LevelsManifest levels;
  try {
    if (m.at("format") != kExrFormatName)
      throw InputError(fmt::format("{}: \"format\" is {}, expected \"{}\"", manifestPath, m.at("format").dump(), kExrFormatName));
    const int version = m.at("format_version").get<int>();
    if (version < kFirstLevelsFormatVersion || version > kLevelsFormatVersion)
      throw InputError(fmt::format("{}: \"format_version\" is {}; levels in EXR slices are formats {} to {}", manifestPath,
                                   m.at("format_version").dump(), kFirstLevelsFormatVersion, kLevelsFormatVersion));
    levels.directories = m.at(kLevelsManifestKey).get<std::vector<std::string>>();
    levels.marginCells = m.at(kMarginKey).get<int>();
    levels.basis = m.at("basis").get<std::string>();
    if (m.at(kLevelRatioKey).get<int>() != kLevelRatio)
      throw InputError(fmt::format("{}: \"{}\" is not {}, the only ratio this reader knows", manifestPath, kLevelRatioKey,
                                   kLevelRatio));
  } catch (const nlohmann::json::exception& e) {
    throw InputError(fmt::format("{}: {}", manifestPath, oneLine(e.what())));
  }
  if (levels.directories.empty() || levels.directories.size() > std::size_t(kMaxLevels))
    throw InputError(fmt::format("{}: \"{}\" lists {} levels; a volume has 1 to {}", manifestPath, kLevelsManifestKey,
                                 levels.directories.size(), kMaxLevels));
  for (std::size_t k = 0; k < levels.directories.size(); ++k)
    if (levels.directories[k] != levelDirectory(int(k)))
      throw InputError(fmt::format("{}: level {} is \"{}\", expected \"{}\"", manifestPath, k, levels.directories[k],
                                   levelDirectory(int(k))));
  return levels;
}

// What a level's manifest says of its size and contents, read before any level's slices so that
// the levels are checked together, and against each other, first.
struct LevelSize {
  ProbeGrid grid;
  std::size_t bricks = 0;
  std::string basis;
  int level = -1, coefficientsPerProbe = 0, visibilityPerProbe = 0;
  bool probeStates = false;
};

LevelSize levelSize(const nlohmann::json& level, const std::string& manifestPath) {
  LevelSize size;
  try {
    const auto dims = level.at("dims").get<std::vector<int>>();
    const auto origin = level.at("origin").get<std::vector<double>>();
    if (dims.size() != 3 || origin.size() != 3)
      throw InputError(fmt::format("{}: \"dims\" and \"origin\" need three numbers each", manifestPath));
    size.grid.dims = Eigen::Vector3i(dims[0], dims[1], dims[2]);
    size.grid.origin = Eigen::Vector3d(origin[0], origin[1], origin[2]);
    size.grid.spacing = level.at("spacing").get<double>();
    size.bricks = level.at("atlas").at("bricks").size();
    size.basis = level.at("basis").get<std::string>();
    size.level = level.at("level").get<int>();
    size.coefficientsPerProbe = level.at("coefficients_per_probe").get<int>();
    size.visibilityPerProbe = level.at("visibility_per_probe").get<int>();
    size.probeStates = level.at("probe_states").get<bool>();
  } catch (const nlohmann::json::exception& e) {
    throw InputError(fmt::format("{}: {}", manifestPath, oneLine(e.what())));
  }
  return size;
}

// A level that does not belong with the others: another basis or level number, other counts.
void requireConsistent(const LevelSize& size, int level, const LevelSize& first, const std::string& basis,
                       const std::string& manifestPath) {
  if (size.level != level) throw InputError(fmt::format("{}: \"level\" is {}, expected {}", manifestPath, size.level, level));
  if (size.basis != basis)
    throw InputError(fmt::format("{}: \"basis\" is {}, but the volume's manifest says {}", manifestPath, size.basis, basis));
  if (!size.probeStates) throw InputError(fmt::format("{}: \"probe_states\" is false; a level needs them", manifestPath));
  if (size.coefficientsPerProbe != first.coefficientsPerProbe || size.visibilityPerProbe != first.visibilityPerProbe)
    throw InputError(fmt::format("{}: {} coefficients and {} visibility numbers per probe, but level 0 has {} and {}",
                                 manifestPath, size.coefficientsPerProbe, size.visibilityPerProbe,
                                 first.coefficientsPerProbe, first.visibilityPerProbe));
}

}  // namespace

void writeAdaptiveExrSlices(const AdaptiveVolume& volume, const Basis& basis, const std::string& directory,
                            ExrPrecision precision) {
  requireNoDistanceMap(volume);
  AtomicDirectory out(directory, replaceableExrDirectory);
  nlohmann::json levels = nlohmann::json::array();
  for (std::size_t k = 0; k < volume.levels.size(); ++k) {
    const std::string name = levelDirectory(int(k));
    const std::filesystem::path dir = std::filesystem::path(out.temporaryPath()) / name;
    std::error_code ec;
    if (!std::filesystem::create_directory(dir, ec))
      throw InputError(fmt::format("{}: cannot create {}: {}", directory, name, ec.message()));
    const Volume& level = volume.levels[k];
    std::vector<std::int64_t> bricks = heldBricksInOrder(level);
    std::vector<std::uint8_t> masks;
    if (level.rows.holdsPartialBricks())
      for (const std::int64_t b : bricks) masks.push_back(level.rows.subBricks(level.grid, b));
    const BrickAtlas atlas = BrickAtlas::of(std::move(bricks), std::move(masks));
    const std::string version = std::to_string(kLevelsFormatVersion);
    writeSliceSet(volume.levels[k], basis, dir.string(), precision, &atlas,
                  {{"format_version", kLevelsFormatVersion}, {"level", k}, {"metadata", {{"baker.format_version", version}}}});
    levels.push_back(name);
  }
  const nlohmann::json manifest = {{"format", kExrFormatName},
                                   {"format_version", kLevelsFormatVersion},
                                   {"basis", basis.name()},
                                   {kLevelsManifestKey, levels},
                                   {kLevelRatioKey, kLevelRatio},
                                   {kMarginKey, volume.marginCells}};
  out.writeFile("manifest.json", manifest.dump(2) + "\n");
  out.commit();
}

AdaptiveVolume readAdaptiveExrSlices(const std::string& path) {
  const nlohmann::json m = readExrManifest(path);
  AdaptiveVolume volume;
  if (!m.contains(kLevelsManifestKey)) {
    volume.levels.push_back(readExrSlices(path));
    return volume;
  }
  const std::filesystem::path root = exrVolumeDirectory(path);
  const std::string manifestPath = (root / "manifest.json").string();
  const LevelsManifest levels = levelsManifest(m, manifestPath);
  const std::unique_ptr<Basis> basis = basisInFile(levels.basis, {}, manifestPath);
  LevelChecks checks(*basis, manifestPath);
  checks.margin(levels.marginCells, kMarginKey);
  volume.marginCells = levels.marginCells;
  std::vector<nlohmann::json> manifests;
  LevelSize first;
  for (std::size_t k = 0; k < levels.directories.size(); ++k) {
    const std::string dir = (root / levels.directories[k]).string();
    manifests.push_back(readExrManifest(dir));
    const std::string levelManifest = levels.directories[k] + "/manifest.json";
    const LevelSize size = levelSize(manifests.back(), levelManifest);
    if (k == 0) first = size;
    requireConsistent(size, int(k), first, levels.basis, levelManifest);
    checks.grid(int(k), size.grid, levelManifest + ": ");
    checks.held(int(k), size.bricks);
  }
  for (std::size_t k = 0; k < levels.directories.size(); ++k)
    volume.levels.push_back(readAtlasSliceSet((root / levels.directories[k]).string(), manifests[k]));
  return volume;
}

}  // namespace baker
