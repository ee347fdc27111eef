#include "viewer/ViewerPage.h"

#include <fmt/format.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "basis/StoredSignal.h"
#include "common/Error.h"
#include "formats/AtomicFile.h"
#include "formats/ReconstructionData.h"
#include "formats/VolumeLayout.h"
#include "formats/VolumeMetadata.h"
#include "formats/VolumeReader.h"
#include "viewer/SceneCopy.h"

namespace baker {
namespace {

constexpr const char* kPageMarker = "volume.json";
constexpr const char* kPageFormat = "baker-viewer-volume";
const char* const kBundleFiles[] = {"index.html", "viewer.js"};

bool isViewerPage(const std::string& path) { return directoryHolds(path, kPageMarker) && directoryHolds(path, "index.html"); }

template <typename T>
void appendLittleEndian(std::string& bytes, const T* values, std::size_t count) {
  static_assert(sizeof(T) == 4, "32-bit values");
  for (std::size_t i = 0; i < count; ++i) {
    std::uint32_t word;
    std::memcpy(&word, values + i, 4);
    for (int b = 0; b < 4; ++b) bytes.push_back(char(word >> (8 * b)));
  }
}

// volume.bin, level after level: the probes the level holds, one row each in the level's row
// order (ProbeRows), as coefficients, visibility, states (one int32 each), offsets (three floats
// each), distance moments (the map's values per probe, when the volume holds them: leak-aware
// reading) and, for a level that holds only some bricks, each row's probe (i, j, k) on the
// level's grid (three int32: a grid may hold more probes than an int32 counts) and a byte per
// brick of 8³ (x fastest) with a bit per sub-brick of 4³ held. Each section starts on a multiple
// of four bytes; the level's "sections" say where.
nlohmann::json appendLevel(const Volume& v, int level, std::string& bytes) {
  const std::size_t rows = std::size_t(v.rows.count(v.grid));
  nlohmann::json sections = nlohmann::json::object();
  const auto section = [&](const char* name, std::size_t count) {
    bytes.resize((bytes.size() + 3) / 4 * 4, '\0');
    sections[name] = {{"byte_offset", bytes.size()}, {"count", count}};
  };
  section("coefficients", v.coefficients.size());
  appendLittleEndian(bytes, v.coefficients.data(), v.coefficients.size());
  section("visibility", v.visibility.size());
  appendLittleEndian(bytes, v.visibility.data(), v.visibility.size());
  std::vector<std::int32_t> states(rows, std::int32_t(ProbeState::Valid));
  for (std::size_t r = 0; r < v.states.size(); ++r) states[r] = std::int32_t(v.states[r]);
  section("states", states.size());
  appendLittleEndian(bytes, states.data(), states.size());
  std::vector<float> offsets(3 * rows, 0.0f);
  for (std::size_t r = 0; r < v.offsets.size(); ++r)
    for (int a = 0; a < 3; ++a) offsets[3 * r + a] = v.offsets[r][a];
  section("offsets", offsets.size());
  appendLittleEndian(bytes, offsets.data(), offsets.size());
  if (v.distanceMomentsPerProbe() > 0) {
    section("distance_moments", v.distanceMoments.size());
    appendLittleEndian(bytes, v.distanceMoments.data(), v.distanceMoments.size());
  }
  const ProbeGrid& g = v.grid;
  if (!v.rows.holdsEveryProbe()) {
    std::vector<std::int32_t> probes(3 * rows);
    for (std::size_t r = 0; r < rows; ++r) {
      const std::int64_t p = v.rows.probeAt(g, std::int64_t(r));
      const std::int64_t nx = g.dims.x(), ny = g.dims.y();
      probes[3 * r] = std::int32_t(p % nx), probes[3 * r + 1] = std::int32_t(p / nx % ny);
      probes[3 * r + 2] = std::int32_t(p / (nx * ny));
    }
    section("probes", probes.size());
    appendLittleEndian(bytes, probes.data(), probes.size());
    section("sub_bricks_held", std::size_t(g.brickCount()));
    for (std::int64_t b = 0; b < g.brickCount(); ++b) bytes.push_back(char(v.rows.subBricks(g, b)));
  }
  return {{"level", level},
          {"origin", {g.origin.x(), g.origin.y(), g.origin.z()}},
          {"spacing", g.spacing},
          {"dims", {g.dims.x(), g.dims.y(), g.dims.z()}},
          {"rows", rows},
          {"sections", sections}};
}

nlohmann::json describe(const AdaptiveVolume& levels, const ViewerPage& page, const std::string& sceneUrl,
                        nlohmann::json levelLayouts) {
  const Volume& v = levels.coarsest();
  const std::unique_ptr<Basis> basis = basisOf(v);
  const nlohmann::json metadata = describingMetadataJson(v, *basis);
  const ProbeGrid& g = v.grid;
  return {{"format", kPageFormat},
          {"volume", std::filesystem::path(page.volumePath).filename().string()},
          {"basis", v.basisName},
          {"reconstruction", reconstructionData(*basis, storedSignalOf(v.settings))},
          // The coarsest level's grid; every level's is in "levels".
          {"dims", {g.dims.x(), g.dims.y(), g.dims.z()}},
          {"origin", {g.origin.x(), g.origin.y(), g.origin.z()}},
          {"spacing", g.spacing},
          {"coefficients_per_probe", v.coefficientsPerProbe},
          {"visibility_per_probe", v.visibilityPerProbe},
          {"probe_states", v.hasProbeStates()},
          // What leak-aware reading needs of the map (its moments: the first 2·size² values of
          // each probe's values_per_probe); null when the volume holds none.
          {"distance_map", v.distanceMomentsPerProbe() > 0
                               ? nlohmann::json({{"size", v.distanceMap.size},
                                                 {"cap", v.distanceMap.cap},
                                                 {"values_per_probe", v.distanceMomentsPerProbe()}})
                               : nlohmann::json(nullptr)},
          {"levels", std::move(levelLayouts)},
          {"units", "irradiance E(n) = integral of L(w) max(0, n.w) dw, in the scene's radiance units times "
                    "steradians"},
          {"scene", sceneUrl.empty() ? nlohmann::json(nullptr) : nlohmann::json(sceneUrl)},
          {"binary", {{"file", "volume.bin"}}},
          {"metadata", metadata}};
}

}  // namespace

std::string sceneOfVolume(const Volume& volume, const std::string& volumePath, const std::string& given) {
  std::error_code ec;
  if (!given.empty()) {
    if (!std::filesystem::is_regular_file(given, ec)) throw InputError(fmt::format("{}: scene file does not exist", given));
    return given;
  }
  const auto named = volume.settings.find("scene");
  if (named == volume.settings.end() || named->second.empty()) return "";
  // Beside the volume: beside its file, or beside its directory (EXR slices, an engine's export),
  // or beside the directory of the file inside it that was named.
  std::filesystem::path where = std::filesystem::absolute(volumePath, ec).lexically_normal();
  if (where.filename().empty()) where = where.parent_path();  // "room_exr/" names room_exr
  if (!std::filesystem::is_directory(where, ec) && volumeFormatOf(volumePath) != "vdb") where = where.parent_path();
  const std::filesystem::path beside = where.parent_path() / std::filesystem::path(named->second).filename();
  return std::filesystem::is_regular_file(beside, ec) ? beside.string() : "";
}

std::string viewerBundleDirectory() {
  std::vector<std::string> candidates;
  std::error_code ec;
  if (const char* chosen = std::getenv("BAKER_VIEWER_DIR"); chosen && *chosen) {
    candidates.push_back(chosen);
  } else {
    const std::filesystem::path executable = std::filesystem::read_symlink("/proc/self/exe", ec);
    if (!ec) candidates.push_back((executable.parent_path() / "viewer").string());
    candidates.push_back(BAKER_VIEWER_BUILD_DIR);
  }
  std::string looked;
  for (const std::string& dir : candidates) {
    bool complete = true;
    for (const char* file : kBundleFiles) complete = complete && directoryHolds(dir, file);
    if (complete) return dir;
    looked += (looked.empty() ? "" : ", ") + dir;
  }
  throw std::runtime_error(fmt::format("the viewer's page (index.html and viewer.js) is missing (looked in {}): build "
                                       "the target baker_viewer_bundle (scripts/setup.sh does), or set "
                                       "BAKER_VIEWER_DIR to its directory",
                                       looked));
}

void writeViewerPage(const AdaptiveVolume& levels, const ViewerPage& page) {
  // The page shades with the browser decoder, which reconstructs irradiance volumes.
  if (storedSignalOf(levels.coarsest().settings) == StoredSignal::Radiance)
    throw InputError(fmt::format("{}: holds radiance (setting signal), which the viewer's decoder does not "
                                 "reconstruct; view a bake of the same scene whose signal is irradiance",
                                 page.volumePath));
  const std::string bundle = viewerBundleDirectory();
  AtomicDirectory out(page.outDirectory, isViewerPage);
  const std::filesystem::path dir = out.temporaryPath();
  for (const char* file : kBundleFiles) std::filesystem::copy_file(std::filesystem::path(bundle) / file, dir / file);
  const std::string sceneUrl = page.scenePath.empty() ? "" : copyScene(page.scenePath, (dir / "scene").string());
  std::string bytes;
  nlohmann::json levelLayouts = nlohmann::json::array();
  for (std::size_t l = 0; l < levels.levels.size(); ++l) levelLayouts.push_back(appendLevel(levels.levels[l], int(l), bytes));
  out.writeFile("volume.bin", bytes);
  out.writeFile(kPageMarker, describe(levels, page, sceneUrl, std::move(levelLayouts)).dump(1) + "\n");
  out.commit();
}

}  // namespace baker
