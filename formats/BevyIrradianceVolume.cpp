#include "formats/BevyIrradianceVolume.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>

#include "basis/BasisRegistry.h"
#include "common/Error.h"
#include "formats/AtomicFile.h"
#include "formats/CellCentredBox.h"
#include "formats/Ktx2File.h"
#include "formats/Rgb9e5.h"
#include "formats/VolumeHeader.h"
#include "formats/VolumeLayout.h"
#include "formats/VolumeMetadata.h"
#include "formats/VolumeReconstruction.h"

namespace baker {
namespace {

constexpr const char* kTextureName = "irradiance_volume.ktx2";
constexpr const char* kSidecarName = "irradiance_volume.json";
constexpr const char* kFormatName = "baker-bevy-irradiance-volume";
constexpr const char* kBevyVersions = "Bevy 0.13 to 0.19 (bevy::light::IrradianceVolume since 0.17, bevy::pbr before)";
// The texture stores E/π: Bevy multiplies by this and the diffuse colour, with no 1/π of its own.
constexpr double kIntensity = 1.0;

// The six faces in the order of the ambient-cube basis: +X, −X, +Y, −Y, +Z, −Z.
Eigen::Vector3d faceNormal(int face) {
  Eigen::Vector3d n = Eigen::Vector3d::Zero();
  n[face / 2] = face % 2 == 0 ? 1.0 : -1.0;
  return n;
}

// The texel of face `face` of probe (i, j, k) in Bevy's layout.
std::size_t texelIndex(const ProbeGrid& g, int i, int j, int k, int face) {
  const std::size_t x = i, y = j + (face % 2 == 1 ? g.dims.y() : 0), z = k + (face / 2) * g.dims.z();
  return x + std::size_t(g.dims.x()) * (y + 2 * std::size_t(g.dims.y()) * z);
}

}  // namespace

std::string bevyConversion(const Basis& basis, StoredSignal signal) {
  if (basis.family() == "ambient-cube" && signal == StoredSignal::Irradiance)
    return "ambient-cube stored as it is (each face E(axis)/pi); exact";
  return fmt::format("{} {} converted to Bevy's ambient cube by its irradiance at the six axes{} (each face "
                     "E(axis)/pi): exact at the axes, and between them Bevy blends the six faces by n^2",
                     basis.name(), storedSignalName(signal),
                     signal == StoredSignal::Radiance ? ", each function's diffuse response" : "");
}

namespace {

nlohmann::json sidecarOf(const Volume& v, const Basis& basis, const EngineExport& report) {
  const CellCentredBox box = cellCentredBox(v.grid);
  const nlohmann::json metadata = exportedMetadataJson(v, basis, *makeBasis("ambient-cube"));
  return {{"format", kFormatName},
          {"format_version", kVolumeFormatVersion},
          {"bevy", kBevyVersions},
          {"texture", kTextureName},
          {"resolution", {box.resolution.x(), box.resolution.y(), box.resolution.z()}},
          {"transform", {{"translation", {box.centre.x(), box.centre.y(), box.centre.z()}},
                         {"rotation", {0.0, 0.0, 0.0, 1.0}},
                         {"scale", {box.size.x(), box.size.y(), box.size.z()}}}},
          {"intensity", kIntensity},
          {"stored", "per probe and face F (+X, -X, +Y, -Y, +Z, -Z): E(F)/pi, E(n) = integral of L(w) max(0, n.w) "
                     "dw in the scene's units; Bevy shades with texel * intensity * diffuse colour"},
          {"probe_placement", "cell centres of the unit cube -0.5..0.5 that the transform maps onto the grid: probe "
                              "(i, j, k) at translation + scale * ((i + 0.5) / Rx - 0.5, ...)"},
          {"export", {{"conversion", report.conversion}, {"clamped_values", report.clampedValues}}},
          {"metadata", metadata}};
}

Ktx2Texture3D textureOf(const Volume& v, EngineExport& report) {
  const ProbeGrid& g = v.grid;
  Ktx2Texture3D t;
  t.vkFormat = kVkFormatE5B9G9R9;
  t.typeSize = 4;
  t.width = std::uint32_t(g.dims.x());
  t.height = std::uint32_t(2 * g.dims.y());
  t.depth = std::uint32_t(3 * g.dims.z());
  t.dataFormatDescriptor = rgb9e5DataFormatDescriptor();
  t.keyValues = {{"KTXwriter", fmt::format("baker {}", BAKER_VERSION)}};
  t.texels.assign(std::size_t(t.width) * t.height * t.depth * 4, 0);
  const std::vector<bool> stored = storedBricks(v);
  const VolumeReconstruction reading(v);
  for (int k = 0; k < g.dims.z(); ++k)
    for (int j = 0; j < g.dims.y(); ++j)
      for (int i = 0; i < g.dims.x(); ++i) {
        // Bricks a file leaves out (storedBricks) read as zeros in every format.
        if (!stored[g.brickOf(i, j, k)]) continue;
        const float* coefficients = v.probe(g.linearIndex(i, j, k));
        for (int face = 0; face < 6; ++face) {
          const Eigen::Vector3f e = reading.irradiance(coefficients, faceNormal(face));
          const Rgb9e5Packing texel = packRgb9e5((e.cast<double>() / (M_PI * kIntensity)).cast<float>());
          report.clampedValues += texel.clamped;
          const std::size_t at = 4 * texelIndex(g, i, j, k, face);
          for (int b = 0; b < 4; ++b) t.texels[at + b] = std::uint8_t(texel.bits >> (8 * b));
        }
      }
  if (report.clampedValues > 0)
    report.clampedBecause =
        "RGB9E5 holds 0 to 65408: the irradiance at an axis dipped below 0 (ringing near a bright source, which a "
        "basis of non-negative functions fitted non-negative avoids) or rose above 65408";
  return t;
}

}  // namespace

EngineExport writeBevyIrradianceVolume(const Volume& volume, const Basis& basis, const std::string& directory) {
  requireFiniteVolume(volume);
  EngineExport report;
  report.engine = "bevy";
  report.conversion = bevyConversion(basis, storedSignalOf(volume.settings));
  const Ktx2Texture3D texture = textureOf(volume, report);
  if (std::max({texture.width, texture.height, texture.depth}) > std::uint32_t(kCommon3dTextureLimit))
    report.warnings.push_back(fmt::format("the texture is {} × {} × {}: Bevy (wgpu's default limits) takes 3D textures "
                                          "of at most {} texels a side; use a larger spacing or split the volume",
                                          texture.width, texture.height, texture.depth, kCommon3dTextureLimit));
  const std::string sidecar = sidecarOf(volume, basis, report).dump(2);
  AtomicDirectory out(directory, isBevyIrradianceVolumeDirectory);
  const std::vector<std::uint8_t> ktx2 = encodeKtx2(texture);
  out.writeFile(kTextureName, std::string(ktx2.begin(), ktx2.end()));
  out.writeFile(kSidecarName, sidecar);
  out.commit();
  return report;
}

bool isBevyIrradianceVolumeDirectory(const std::string& path) { return directoryHolds(path, kSidecarName); }

namespace {

// The probe grid and intensity the sidecar describes; checked before any texel is believed.
VolumeHeader headerOf(const nlohmann::json& j, const std::string& where, double& intensity) {
  if (j.at("format") != kFormatName)
    throw InputError(fmt::format("{}: \"format\" is {}, expected \"{}\"", where, j.at("format").dump(), kFormatName));
  const nlohmann::json& transform = j.at("transform");
  // Bevy picks the six faces by the world-space normal: only an unrotated volume shades right.
  if (transform.at("rotation").get<std::vector<double>>() != std::vector<double>{0.0, 0.0, 0.0, 1.0})
    throw InputError(fmt::format("{}: \"transform.rotation\" must be the identity (0, 0, 0, 1)", where));
  CellCentredBox box;
  box.resolution = jsonResolution(j.at("resolution"), where, "resolution");
  box.centre = jsonVector3(transform.at("translation"), where, "transform.translation");
  box.size = jsonVector3(transform.at("scale"), where, "transform.scale");
  VolumeHeader header;
  header.basisName = "ambient-cube";
  header.coefficientsPerProbe = 18;
  header.grid = probeGridOf(box, where);
  intensity = j.at("intensity").get<double>();
  if (!(intensity > 0.0) || !std::isfinite(intensity))
    throw InputError(fmt::format("{}: \"intensity\" must be a positive number", where));
  const double version = j.at("format_version").get<double>();
  if (!(version >= 0.0 && version <= 1e6 && version == std::floor(version)))
    throw InputError(fmt::format("{}: \"format_version\" {} is not a format version", where, version));
  header.text.push_back({"baker.format_version", std::to_string(int(version))});
  for (const auto& [key, value] : j.at("metadata").items())
    if (key != "baker.format_version") header.text.push_back({key, value.get<std::string>()});
  return header;
}

// The texture's bytes, after checking that the file is no larger than the grid's texels and a
// KTX2 header, descriptor and key/value data could make it: a file is read whole, so its size is
// believed only when the sidecar's grid agrees with it.
std::vector<std::uint8_t> readTexture(const std::string& path, const ProbeGrid& g) {
  constexpr std::uintmax_t kMostHeaderBytes = 1 << 16;
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw InputError(fmt::format("{}: the texture is missing", path));
  const std::uintmax_t texels = 4 * std::uintmax_t(g.dims.x()) * (2 * std::uintmax_t(g.dims.y())) * (3 * std::uintmax_t(g.dims.z()));
  const std::uintmax_t bytes = std::filesystem::file_size(path, ec);
  if (ec || bytes > texels + kMostHeaderBytes)
    throw InputError(fmt::format("{}: {} bytes, more than the {} × {} × {} probes of {} need", path, bytes, g.dims.x(),
                                 g.dims.y(), g.dims.z(), kSidecarName));
  std::ifstream in(path, std::ios::binary);
  return std::vector<std::uint8_t>(std::istreambuf_iterator<char>(in), {});
}

}  // namespace

Volume readBevyIrradianceVolume(const std::string& path) {
  std::filesystem::path dir = path;
  if (dir.filename() == kTextureName || dir.filename() == kSidecarName) dir = dir.parent_path();
  const std::string sidecarPath = (dir / kSidecarName).string();
  std::ifstream in(sidecarPath);
  if (!in) throw InputError(fmt::format("{}: no {} (not a Bevy irradiance volume written by baker)", path, kSidecarName));
  VolumeHeader header;
  double intensity = 1.0;
  try {
    header = headerOf(nlohmann::json::parse(in), sidecarPath, intensity);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(fmt::format("{}: {}", sidecarPath, oneLine(e.what())));
  }
  const ProbeGrid& g = header.grid;
  const std::string texturePath = (dir / kTextureName).string();
  const Ktx2Texture3D t = decodeKtx2(readTexture(texturePath, g), texturePath);
  if (t.vkFormat != kVkFormatE5B9G9R9 || t.typeSize != 4)
    throw InputError(fmt::format("{}: vkFormat {}, expected {} (E5B9G9R9_UFLOAT_PACK32)", texturePath, t.vkFormat,
                                 kVkFormatE5B9G9R9));
  if (std::int64_t(t.width) != g.dims.x() || std::int64_t(t.height) != 2 * std::int64_t(g.dims.y()) ||
      std::int64_t(t.depth) != 3 * std::int64_t(g.dims.z()) || t.texels.size() != std::size_t(t.width) * t.height * t.depth * 4)
    throw InputError(fmt::format("{}: {} × {} × {} texels, but {} probes of {} × {} × {} need {} × {} × {}", texturePath,
                                 t.width, t.height, t.depth, kSidecarName, g.dims.x(), g.dims.y(), g.dims.z(),
                                 g.dims.x(), 2 * g.dims.y(), 3 * g.dims.z()));
  Volume volume = header.emptyVolume(sidecarPath);
  for (int k = 0; k < g.dims.z(); ++k)
    for (int j = 0; j < g.dims.y(); ++j)
      for (int i = 0; i < g.dims.x(); ++i)
        for (int face = 0; face < 6; ++face) {
          const std::size_t at = 4 * texelIndex(g, i, j, k, face);
          const std::uint32_t bits = std::uint32_t(t.texels[at]) | std::uint32_t(t.texels[at + 1]) << 8 |
                                     std::uint32_t(t.texels[at + 2]) << 16 | std::uint32_t(t.texels[at + 3]) << 24;
          const Eigen::Vector3f faceValue = unpackRgb9e5(bits);
          float* probe = volume.coefficients.data() + g.linearIndex(i, j, k) * header.coefficientsPerProbe;
          for (int c = 0; c < 3; ++c) probe[6 * c + face] = float(double(faceValue[c]) * M_PI * intensity);
        }
  requireFiniteValues(volume, sidecarPath);
  return volume;
}

}  // namespace baker
