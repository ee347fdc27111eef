#include "formats/ThreeJsProbeGrid.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "basis/BasisRegistry.h"
#include "basis/StoredSignal.h"
#include "common/Error.h"
#include "formats/AtomicFile.h"
#include "formats/CellCentredBox.h"
#include "formats/HalfFloat.h"
#include "formats/VolumeHeader.h"
#include "formats/VolumeLayout.h"
#include "formats/VolumeMetadata.h"

namespace baker {
namespace {

constexpr const char* kJsonName = "light_probe_grid.json";
constexpr const char* kAtlasName = "light_probe_grid.bin";
constexpr const char* kFormatName = "baker-threejs-light-probe-grid";
constexpr const char* kThreeVersion = "three@0.187.0 (r187)";
constexpr int kShCount = 9;
constexpr int kValuesPerProbe = 3 * kShCount;
// The JSON's integers: the largest coefficient gets this many steps, so that the integers keep
// a float's precision (three.js's own toJSON uses a fixed 4096, too coarse for dim scenes).
constexpr double kIntegerSteps = 16777216.0;  // 2^24

// Irradiance E = Â_l · radiance band by band, for the clamped cosine: Â = π, 2π/3, π/4.
double cosineFactor(int shIndex) {
  const int band = shIndex == 0 ? 0 : shIndex < 4 ? 1 : 2;
  return band == 0 ? M_PI : band == 1 ? 2.0 * M_PI / 3.0 : M_PI / 4.0;
}

int shOrderOf(const Basis& basis) { return int(std::lround(std::sqrt(double(basis.coefficientCount(0))))) - 1; }

// The 27 radiance coefficients of probe p in three.js's order (SH function k, channel c at
// 3k + c); SH functions the basis lacks are 0. A radiance volume holds them as they are; an
// irradiance volume's are divided by the clamped cosine's band factors.
void radianceOf(const Volume& v, const Basis& basis, std::int64_t p, double* out) {
  const int count = basis.coefficientCount(0);
  const bool radiance = storedSignalOf(v.settings) == StoredSignal::Radiance;
  for (int k = 0; k < kShCount; ++k)
    for (int c = 0; c < 3; ++c) {
      const double value = k < count ? double(v.probe(p)[basis.coefficientOffset(c) + k]) : 0.0;
      out[3 * k + c] = radiance ? value : value / cosineFactor(k);
    }
}

nlohmann::json bakerSection(const Volume& v, const Basis& basis, const EngineExport& report, double scale) {
  const nlohmann::json metadata = exportedMetadataJson(v, basis, *makeBasis("sh-l2"));
  const ProbeGrid& g = v.grid;
  return {{"format", kFormatName},
          {"format_version", kVolumeFormatVersion},
          {"three", kThreeVersion},
          {"stored", "radiance: coefficients of L(w) in three.js's SphericalHarmonics3 functions (shIndex*3 + "
                     "channel), which its shader convolves with the clamped cosine into irradiance E(n); "
                     "data[i] / scale"},
          {"probe_placement", "cell centres: probe (i, j, k) at position - size/2 + (i + 0.5, j + 0.5, k + 0.5) * "
                              "size / resolution"},
          {"atlas", {{"file", kAtlasName},
                     {"size", {g.dims.x(), g.dims.y(), kThreeJsAtlasSubVolumes * (g.dims.z() + 2)}},
                     {"texel", "RGBA, HalfFloatType, little-endian, x fastest, then y, then layer"}}},
          {"export", {{"conversion", report.conversion}, {"clamped_values", report.clampedValues}}},
          {"integer_scale", scale},
          {"metadata", metadata}};
}

// The atlas's bytes, little-endian halves: layer t·(nz+2) + s of sub-volume t holds, at (i, j), values
// 4t .. 4t+3 of the probe at slice clamp(s − 1, 0, nz − 1).
std::string atlasOf(const ProbeGrid& g, const std::vector<double>& radiance, EngineExport& report) {
  const std::int64_t layers = kThreeJsAtlasSubVolumes * std::int64_t(g.dims.z() + 2);
  std::string bytes(std::size_t(g.dims.x()) * g.dims.y() * layers * 4 * sizeof(std::uint16_t), '\0');
  std::size_t n = 0;
  for (int t = 0; t < kThreeJsAtlasSubVolumes; ++t)
    for (int s = 0; s < g.dims.z() + 2; ++s) {
      const int k = std::clamp(s - 1, 0, g.dims.z() - 1);
      for (int j = 0; j < g.dims.y(); ++j)
        for (int i = 0; i < g.dims.x(); ++i)
          for (int c = 0; c < 4; ++c) {
            const int value = 4 * t + c;
            double x = value < kValuesPerProbe ? radiance[g.linearIndex(i, j, k) * kValuesPerProbe + value] : 0.0;
            if (std::abs(x) > kHalfMax) {
              if (s >= 1 && s <= g.dims.z()) ++report.clampedValues;  // padding layers repeat a slice
              x = std::copysign(double(kHalfMax), x);
            }
            const std::uint16_t half = halfBits(float(x));
            bytes[n++] = char(half & 0xff);
            bytes[n++] = char(half >> 8);
          }
    }
  if (report.clampedValues > 0)
    report.clampedBecause = "radiance coefficients beyond half's ±65504 in the atlas (the JSON keeps them)";
  return bytes;
}

}  // namespace

std::string threeJsRefusal(const Basis& basis) {
  if (basis.family() == "sh" && shOrderOf(basis) <= 2) return "";
  return "three.js's LightProbeGrid holds spherical harmonics up to L2, so it takes sh-l0, sh-l1 and sh-l2";
}

std::string threeJsConversion(const Basis& basis, StoredSignal signal) {
  const char* lacking = shOrderOf(basis) < 2 ? ", the bands the basis lacks zero" : "";
  if (signal == StoredSignal::Radiance)
    return fmt::format("{} radiance stored as three.js's radiance SH L2 as it is{}; exact", basis.name(), lacking);
  return fmt::format(
      "{} irradiance to three.js's radiance SH L2: each band divided by its clamped-cosine factor (pi, 2pi/3, "
      "pi/4){}; exact",
      basis.name(), lacking);
}

EngineExport writeThreeJsProbeGrid(const Volume& volume, const Basis& basis, const std::string& directory) {
  requireFiniteVolume(volume);
  if (const std::string refusal = threeJsRefusal(basis); !refusal.empty())
    throw InputError(fmt::format("{}: {} cannot be written exactly: {}", directory, basis.name(), refusal));
  EngineExport report;
  report.engine = "threejs";
  report.conversion = threeJsConversion(basis, storedSignalOf(volume.settings));
  const ProbeGrid& g = volume.grid;
  const std::vector<bool> stored = storedBricks(volume);
  std::vector<double> radiance(std::size_t(g.probeCount()) * kValuesPerProbe, 0.0);
  double largest = 0.0;
  for (int k = 0; k < g.dims.z(); ++k)
    for (int j = 0; j < g.dims.y(); ++j)
      for (int i = 0; i < g.dims.x(); ++i) {
        // Bricks a file leaves out (storedBricks) read as zeros in every format.
        if (!stored[g.brickOf(i, j, k)]) continue;
        const std::int64_t p = g.linearIndex(i, j, k);
        radianceOf(volume, basis, p, &radiance[p * kValuesPerProbe]);
        for (int c = 0; c < kValuesPerProbe; ++c) largest = std::max(largest, std::abs(radiance[p * kValuesPerProbe + c]));
      }
  const double scale = largest > 0.0 ? std::exp2(std::floor(std::log2(kIntegerSteps / largest))) : 4096.0;
  std::vector<std::int64_t> integers(radiance.size());
  for (std::size_t n = 0; n < radiance.size(); ++n) integers[n] = std::llround(radiance[n] * scale);

  const std::string atlas = atlasOf(g, radiance, report);
  const int atlasDepth = kThreeJsAtlasSubVolumes * (g.dims.z() + 2);
  if (std::max({g.dims.x(), g.dims.y(), atlasDepth}) > kCommon3dTextureLimit)
    report.warnings.push_back(fmt::format("the atlas is {} × {} × {}: most WebGL 2 implementations take 3D textures of "
                                          "at most {} texels a side (all take 256); use a larger spacing",
                                          g.dims.x(), g.dims.y(), atlasDepth, kCommon3dTextureLimit));
  const CellCentredBox box = cellCentredBox(g);
  nlohmann::json json = {
      {"metadata", {{"version", 1}, {"type", "LightProbeGrid"}, {"generator", fmt::format("baker {}", BAKER_VERSION)}}},
      {"width", box.size.x()},
      {"height", box.size.y()},
      {"depth", box.size.z()},
      {"resolution", {box.resolution.x(), box.resolution.y(), box.resolution.z()}},
      {"position", {box.centre.x(), box.centre.y(), box.centre.z()}},
      {"coefficients", {{"scale", scale}, {"data", integers}}},
      {"baker", bakerSection(volume, basis, report, scale)}};

  AtomicDirectory out(directory, isThreeJsProbeGridDirectory);
  out.writeFile(kAtlasName, atlas);
  out.writeFile(kJsonName, json.dump() + "\n");
  out.commit();
  return report;
}

bool isThreeJsProbeGridDirectory(const std::string& path) { return directoryHolds(path, kJsonName); }

namespace {

// The header a baker volume needs, from the JSON: sh-l2 (what three.js holds) whatever the bake's basis.
VolumeHeader headerOf(const nlohmann::json& j, const std::string& where) {
  VolumeHeader header;
  header.basisName = "sh-l2";
  CellCentredBox box;
  box.resolution = jsonResolution(j.at("resolution"), where, "resolution");
  box.centre = jsonVector3(j.at("position"), where, "position");
  box.size = Eigen::Vector3d(j.at("width").get<double>(), j.at("height").get<double>(), j.at("depth").get<double>());
  header.grid = probeGridOf(box, where);
  header.coefficientsPerProbe = kValuesPerProbe;
  // three.js's own toJSON has no "baker" object: its data reads as this version's.
  std::string version = std::to_string(kVolumeFormatVersion);
  if (j.contains("baker") && j["baker"].is_object() && j["baker"].contains("format_version"))
    version = j["baker"]["format_version"].dump();
  header.text.push_back({"baker.format_version", version});
  if (j.contains("baker") && j["baker"].is_object() && j["baker"].contains("metadata"))
    for (const auto& [key, value] : j["baker"]["metadata"].items())
      if (key != "baker.format_version") header.text.push_back({key, value.get<std::string>()});
  return header;
}

void requireAtlas(const std::filesystem::path& dir, const ProbeGrid& g) {
  const std::string atlas = (dir / kAtlasName).string();
  std::error_code ec;
  const std::uintmax_t bytes = std::filesystem::file_size(atlas, ec);
  if (ec) throw InputError(fmt::format("{}: the atlas is missing", atlas));
  const std::uintmax_t expected = std::uintmax_t(g.dims.x()) * g.dims.y() * kThreeJsAtlasSubVolumes *
                                  (std::uintmax_t(g.dims.z()) + 2) * 4 * sizeof(std::uint16_t);
  if (bytes != expected)
    throw InputError(fmt::format("{}: {} bytes, but a {} × {} × {} grid's atlas has {}", atlas, bytes, g.dims.x(),
                                 g.dims.y(), g.dims.z(), expected));
}

}  // namespace

Volume readThreeJsProbeGrid(const std::string& path) {
  std::filesystem::path dir = path;
  if (dir.filename() == kJsonName) dir = dir.parent_path();
  const std::string jsonPath = (dir / kJsonName).string();
  std::ifstream in(jsonPath);
  if (!in) throw InputError(fmt::format("{}: no {} (not a three.js light probe grid)", path, kJsonName));
  try {
    const nlohmann::json j = nlohmann::json::parse(in);
    if (j.at("metadata").at("type") != "LightProbeGrid")
      throw InputError(fmt::format("{}: metadata.type is {}, expected \"LightProbeGrid\"", jsonPath,
                                   j.at("metadata").at("type").dump()));
    const VolumeHeader header = headerOf(j, jsonPath);
    const double scale = j.at("coefficients").at("scale").get<double>();
    if (!(scale > 0.0) || !std::isfinite(scale))
      throw InputError(fmt::format("{}: coefficients.scale must be a positive number", jsonPath));
    const nlohmann::json& data = j.at("coefficients").at("data");
    if (!data.is_array() || data.size() != std::size_t(header.grid.probeCount()) * kValuesPerProbe)
      throw InputError(fmt::format("{}: coefficients.data holds {} values, expected 27 per probe ({})", jsonPath,
                                   data.is_array() ? data.size() : 0, header.grid.probeCount() * kValuesPerProbe));
    requireAtlas(dir, header.grid);
    Volume volume = header.emptyVolume(jsonPath);
    for (std::int64_t p = 0; p < header.grid.probeCount(); ++p)
      for (int k = 0; k < kShCount; ++k)
        for (int c = 0; c < 3; ++c) {
          const nlohmann::json& value = data[p * kValuesPerProbe + 3 * k + c];
          if (!value.is_number())
            throw InputError(fmt::format("{}: coefficients.data[{}] is not a number", jsonPath, p * kValuesPerProbe + 3 * k + c));
          volume.coefficients[p * kValuesPerProbe + c * kShCount + k] =
              float(value.get<double>() / scale * cosineFactor(k));
        }
    requireFiniteValues(volume, jsonPath);
    return volume;
  } catch (const nlohmann::json::exception& e) {
    throw InputError(fmt::format("{}: {}", jsonPath, oneLine(e.what())));
  }
}

}  // namespace baker
