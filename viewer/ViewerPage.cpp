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

// volume.bin: coefficients, then visibility, then states (one int32 each), then offsets (three
// floats each); volume.json says where each begins.
std::string binaryOf(const Volume& v, nlohmann::json& layout) {
  std::string bytes;
  const std::size_t probes = std::size_t(v.grid.probeCount());
  const auto section = [&](const char* name, std::size_t count) {
    layout[name] = {{"byte_offset", bytes.size()}, {"count", count}};
  };
  section("coefficients", v.coefficients.size());
  appendLittleEndian(bytes, v.coefficients.data(), v.coefficients.size());
  section("visibility", v.visibility.size());
  appendLittleEndian(bytes, v.visibility.data(), v.visibility.size());
  std::vector<std::int32_t> states(probes, std::int32_t(ProbeState::Valid));
  for (std::size_t p = 0; p < v.states.size(); ++p) states[p] = std::int32_t(v.states[p]);
  section("states", states.size());
  appendLittleEndian(bytes, states.data(), states.size());
  std::vector<float> offsets(3 * probes, 0.0f);
  for (std::size_t p = 0; p < v.offsets.size(); ++p)
    for (int a = 0; a < 3; ++a) offsets[3 * p + a] = v.offsets[p][a];
  section("offsets", offsets.size());
  appendLittleEndian(bytes, offsets.data(), offsets.size());
  return bytes;
}

nlohmann::json describe(const Volume& v, const ViewerPage& page, const std::string& sceneUrl, nlohmann::json layout) {
  const std::unique_ptr<Basis> basis = basisOf(v);
  const nlohmann::json metadata = describingMetadataJson(v, *basis);
  const ProbeGrid& g = v.grid;
  return {{"format", kPageFormat},
          {"volume", std::filesystem::path(page.volumePath).filename().string()},
          {"basis", v.basisName},
          {"reconstruction", reconstructionData(*basis, storedSignalOf(v.settings))},
          {"dims", {g.dims.x(), g.dims.y(), g.dims.z()}},
          {"origin", {g.origin.x(), g.origin.y(), g.origin.z()}},
          {"spacing", g.spacing},
          {"coefficients_per_probe", v.coefficientsPerProbe},
          {"visibility_per_probe", v.visibilityPerProbe},
          {"probe_states", v.hasProbeStates()},
          // One level until volumes are adaptive: the page lists what there is.
          {"levels", nlohmann::json::array({{{"level", 0}, {"spacing", g.spacing}}})},
          {"units", "irradiance E(n) = integral of L(w) max(0, n.w) dw, in the scene's radiance units times "
                    "steradians"},
          {"scene", sceneUrl.empty() ? nlohmann::json(nullptr) : nlohmann::json(sceneUrl)},
          {"binary", {{"file", "volume.bin"}, {"sections", layout}}},
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

void writeViewerPage(const Volume& volume, const ViewerPage& page) {
  // The page shades with the browser decoder, which reconstructs irradiance volumes.
  if (storedSignalOf(volume.settings) == StoredSignal::Radiance)
    throw InputError(fmt::format("{}: holds radiance (setting signal), which the viewer's decoder does not "
                                 "reconstruct; view a bake of the same scene whose signal is irradiance",
                                 page.volumePath));
  const std::string bundle = viewerBundleDirectory();
  AtomicDirectory out(page.outDirectory, isViewerPage);
  const std::filesystem::path dir = out.temporaryPath();
  for (const char* file : kBundleFiles) std::filesystem::copy_file(std::filesystem::path(bundle) / file, dir / file);
  const std::string sceneUrl = page.scenePath.empty() ? "" : copyScene(page.scenePath, (dir / "scene").string());
  nlohmann::json layout = nlohmann::json::object();
  out.writeFile("volume.bin", binaryOf(volume, layout));
  out.writeFile(kPageMarker, describe(volume, page, sceneUrl, layout).dump(1) + "\n");
  out.commit();
}

}  // namespace baker
