#include "formats/ExrSlices.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>

#include "basis/BasisRegistry.h"
#include "common/Error.h"
#include "formats/AtomicFile.h"
#include "formats/BrickAtlas.h"
#include "volume/SubBricks.h"
#include "formats/HalfFloat.h"
#include "formats/VolumeHeader.h"
#include "formats/VolumeLayout.h"
#include "formats/VolumeMetadata.h"
#include "images/ImageFiles.h"

namespace baker {
namespace {

constexpr const char* kManifest = "manifest.json";
constexpr const char* kFormatName = kExrFormatName;

std::string sliceName(int k) { return fmt::format("z{:04}.exr", k); }

// The smallest power of two that brings every coefficient (and the sky's parts of them) within
// half's range.
double coefficientScale(const Volume& v, ExrPrecision precision) {
  if (precision == ExrPrecision::Float) return 1.0;
  double largest = 0.0;
  for (const std::vector<float>* values : {&v.coefficients, &v.skyDirect, &v.skyBounced})
    for (float c : *values) largest = std::max(largest, double(std::abs(c)));
  return largest <= kHalfMax ? 1.0 : std::exp2(std::ceil(std::log2(largest / kHalfMax)));
}

bool scaled(const VolumeGrid& g) {
  return g.kind == VolumeGrid::Kind::Coefficients || g.kind == VolumeGrid::Kind::SkyDirect ||
         g.kind == VolumeGrid::Kind::SkyBounced;
}
bool alwaysFloat(const VolumeGrid& g) {
  return g.kind == VolumeGrid::Kind::ProbeState || g.kind == VolumeGrid::Kind::ProbeOffset;
}

// Where the slices' texels sit in the grid: the grid itself (slice k is z = k), or a brick atlas.
struct SliceLayout {
  const ProbeGrid& grid;
  const BrickAtlas* atlas;

  Eigen::Vector3i texels() const { return atlas ? atlas->texels() : grid.dims; }
  std::int64_t probeAt(int i, int j, int k) const { return atlas ? atlas->probeAt(grid, i, j, k) : grid.linearIndex(i, j, k); }
};

nlohmann::json manifestOf(const Volume& v, const Basis& basis, ExrPrecision precision, double scale,
                          const std::vector<std::string>& channels, const SliceLayout& layout) {
  const nlohmann::json metadata = describingMetadataJson(v, basis);
  std::vector<std::string> slices;
  for (int k = 0; k < layout.texels().z(); ++k) slices.push_back(sliceName(k));
  const ProbeGrid& g = v.grid;
  return {{"format", kFormatName},
          {"format_version", formatVersionOf(v, VolumeFile::ExrSlices)},
          {"basis", basis.name()},
          {"dims", {g.dims.x(), g.dims.y(), g.dims.z()}},
          {"origin", {g.origin.x(), g.origin.y(), g.origin.z()}},
          {"spacing", g.spacing},
          {"coefficients_per_probe", v.coefficientsPerProbe},
          {"visibility_per_probe", v.visibilityPerProbe},
          {"probe_states", v.hasProbeStates()},
          {"precision", precision == ExrPrecision::Half ? "half" : "float"},
          {"coefficient_scale", scale},
          {"channels", channels},
          {"slices", slices},
          {"metadata", metadata}};
}

}  // namespace

bool replaceableExrDirectory(const std::string& path) {
  if (!isExrSliceDirectory(path)) return false;
  try {
    std::ifstream in(std::filesystem::path(path) / kManifest);
    return nlohmann::json::parse(in).value("format", "") == kFormatName;
  } catch (const nlohmann::json::exception&) {
    return false;
  }
}

namespace {

// Opens slice k, named `name` in the manifest, after checking that it is a file in the volume's
// directory holding slice k at the grid's size (InputError naming the slice otherwise).
std::unique_ptr<ImageReader> openSlice(const std::filesystem::path& dir, const std::string& name, int k,
                                       const Eigen::Vector3i& texels, const std::string& manifestPath) {
  if (name.find('/') != std::string::npos || name.find('\\') != std::string::npos)
    throw InputError(fmt::format("{}: slice name \"{}\" must be a file in the volume's directory", manifestPath, name));
  const std::string slicePath = (dir / name).string();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(slicePath, ec)) throw InputError(fmt::format("{}: slice file is missing", slicePath));
  auto image = std::make_unique<ImageReader>(slicePath);
  const ImageHeader& spec = image->header();
  if (spec.width != texels.x() || spec.height != texels.y() || spec.depth != 1)
    throw InputError(fmt::format("{}: {} × {} pixels, expected {} × {}", slicePath, spec.width, spec.height,
                                 texels.x(), texels.y()));
  const int holds = image->intAttribute("baker.slice", -1);
  if (holds != k) throw InputError(fmt::format("{}: holds slice {}, but the manifest lists it as slice {}", slicePath, holds, k));
  return image;
}

}  // namespace

bool isExrSliceDirectory(const std::string& path) { return directoryHolds(path, kManifest); }

void writeSliceSet(const Volume& volume, const Basis& basis, const std::string& directory, ExrPrecision precision,
                   const BrickAtlas* atlas, const nlohmann::json& extra) {
  requireFiniteVolume(volume);
  const std::vector<VolumeGrid> grids = volumeGrids(basis, volume, VolumeFile::ExrSlices);
  const double scale = coefficientScale(volume, precision);
  const PixelType storage = precision == ExrPrecision::Half ? PixelType::Half : PixelType::Float;
  // An atlas holds exactly its bricks; the grid's own layout the bricks a file keeps.
  const std::vector<bool> stored = atlas ? std::vector<bool>() : storedBricks(volume);
  const SliceLayout layout{volume.grid, atlas};

  ImageToWrite slice;
  slice.format = "openexr";
  slice.width = layout.texels().x();
  slice.height = layout.texels().y();
  slice.pixelType = PixelType::Float;
  slice.compression = "zip";
  std::vector<std::pair<const VolumeGrid*, int>> channels;
  for (const VolumeGrid& g : grids)
    for (int c = 0; c < g.components; ++c) {
      channels.push_back({&g, c});
      slice.channelNames.push_back(componentName(g, c));
      slice.channelStorage.push_back(alwaysFloat(g) ? PixelType::Float : storage);
    }
  nlohmann::json manifest = manifestOf(volume, basis, precision, scale, slice.channelNames, layout);
  if (atlas) {
    manifest["atlas"] = {{"slots", {atlas->slots.x(), atlas->slots.y(), atlas->slots.z()}}, {"bricks", atlas->bricks}};
    if (!atlas->masks.empty()) manifest["atlas"]["masks"] = atlas->masks;
  }
  manifest.merge_patch(extra);
  for (const auto& [key, value] : manifest["metadata"].items())
    slice.textAttributes.push_back({key, value.get<std::string>()});
  slice.textAttributes.push_back(
      {"baker.dims", fmt::format("{} {} {}", volume.grid.dims.x(), volume.grid.dims.y(), volume.grid.dims.z())});
  slice.textAttributes.push_back({"baker.origin", fmt::format("{:.17g} {:.17g} {:.17g}", volume.grid.origin.x(),
                                                              volume.grid.origin.y(), volume.grid.origin.z())});
  slice.textAttributes.push_back({"baker.spacing", fmt::format("{:.17g}", volume.grid.spacing)});
  slice.textAttributes.push_back({"baker.coefficient_scale", fmt::format("{:.17g}", scale)});
  // OpenImageIO stamps each EXR with the time it was written (capDate) unless told a time: a
  // fixed one keeps the same volume the same bytes.
  slice.textAttributes.push_back({"DateTime", "1970:01:01 00:00:00"});

  const ProbeGrid& g = volume.grid;
  std::vector<float> pixels(std::size_t(slice.width) * slice.height * channels.size());
  for (int k = 0; k < layout.texels().z(); ++k) {
    std::size_t n = 0;
    for (int j = 0; j < slice.height; ++j)
      for (int i = 0; i < slice.width; ++i) {
        const std::int64_t p = layout.probeAt(i, j, k);
        const bool keep = p >= 0 && (atlas || stored[std::size_t(g.brickOf(i, j, k))]);
        for (const auto& [grid, c] : channels)
          pixels[n++] = keep ? float(gridValue(volume, *grid, c, p) / (scaled(*grid) ? scale : 1.0)) : 0.0f;
      }
    slice.intAttributes = {{"baker.slice", k}};
    slice.pixels = pixels.data();
    const std::string path = (std::filesystem::path(directory) / sliceName(k)).string();
    std::string error;
    if (!writeImage(slice, path, &error))
      throw InputError(fmt::format("{}: cannot write slice {}: {}", directory, k, error));
  }
  const std::filesystem::path manifestPath = std::filesystem::path(directory) / kManifest;
  std::ofstream file(manifestPath);
  file << manifest.dump(2) << "\n";
  file.close();
  if (!file) throw InputError(fmt::format("{}: cannot write", manifestPath.string()));
}

void writeExrSlices(const Volume& volume, const Basis& basis, const std::string& directory, ExrPrecision precision) {
  AtomicDirectory out(directory, replaceableExrDirectory);
  writeSliceSet(volume, basis, out.temporaryPath(), precision, nullptr, nlohmann::json::object());
  out.commit();
}

namespace {

// What a manifest says, before any of it is believed.
struct Manifest {
  VolumeHeader header;
  std::vector<std::string> slices, channelNames;
  double scale = 1.0;
  std::optional<BrickAtlas> atlas;  // a level of an adaptive volume
};

// The atlas a level's manifest gives, checked: bricks in increasing order, slots as
// BrickAtlas::of lays them out (so that a damaged count cannot ask for huge slices).
BrickAtlas readAtlas(const nlohmann::json& a, const std::string& manifestPath) {
  const auto slots = a.at("slots").get<std::vector<int>>();
  const auto bricks = a.at("bricks").get<std::vector<std::int64_t>>();
  for (std::size_t n = 1; n < bricks.size(); ++n)
    if (bricks[n] <= bricks[n - 1])
      throw InputError(fmt::format("{}: \"atlas\".\"bricks\" must be in increasing order", manifestPath));
  std::vector<std::uint8_t> masks;
  if (a.contains("masks")) {
    const auto read = a.at("masks").get<std::vector<int>>();
    if (read.size() != bricks.size())
      throw InputError(fmt::format("{}: \"atlas\".\"masks\" lists {} masks for {} bricks", manifestPath, read.size(),
                                   bricks.size()));
    for (const int mask : read) {
      if (mask < 1 || mask > kEverySubBrick)
        throw InputError(fmt::format("{}: \"atlas\".\"masks\" holds {}; a mask is 1 to 255", manifestPath, mask));
      masks.push_back(std::uint8_t(mask));
    }
  }
  BrickAtlas atlas = BrickAtlas::of(bricks, masks);
  if (slots.size() != 3 || Eigen::Vector3i(slots[0], slots[1], slots[2]) != atlas.slots)
    throw InputError(fmt::format("{}: \"atlas\".\"slots\" must be [{}, {}, {}] for {} bricks", manifestPath,
                                 atlas.slots.x(), atlas.slots.y(), atlas.slots.z(), bricks.size()));
  return atlas;
}

nlohmann::json parseManifest(const std::string& path, const std::string& manifestPath) {
  std::ifstream in(manifestPath);
  if (!in) throw InputError(fmt::format("{}: no {} (not an EXR slice volume)", path, kManifest));
  try {
    return nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(fmt::format("{}: not valid JSON: {}", manifestPath, oneLine(e.what())));
  }
}

Manifest readManifest(const nlohmann::json& m, const std::string& manifestPath) {
  Manifest manifest;
  try {
    if (m.at("format") != kFormatName)
      throw InputError(fmt::format("{}: \"format\" is {}, expected \"{}\"", manifestPath, m.at("format").dump(), kFormatName));
    manifest.header.basisName = m.at("basis").get<std::string>();
    const auto dims = m.at("dims").get<std::vector<int>>();
    const auto origin = m.at("origin").get<std::vector<double>>();
    if (dims.size() != 3 || origin.size() != 3)
      throw InputError(fmt::format("{}: \"dims\" and \"origin\" need three numbers each", manifestPath));
    manifest.header.grid.dims = Eigen::Vector3i(dims[0], dims[1], dims[2]);
    manifest.header.grid.origin = Eigen::Vector3d(origin[0], origin[1], origin[2]);
    manifest.header.grid.spacing = m.at("spacing").get<double>();
    manifest.header.coefficientsPerProbe = m.at("coefficients_per_probe").get<int>();
    manifest.header.visibilityPerProbe = m.at("visibility_per_probe").get<int>();
    manifest.header.hasProbeStates = m.at("probe_states").get<bool>();
    manifest.scale = m.at("coefficient_scale").get<double>();
    manifest.slices = m.at("slices").get<std::vector<std::string>>();
    manifest.channelNames = m.at("channels").get<std::vector<std::string>>();
    manifest.header.text = exrMetadataText(m.at("metadata"));
    if (m.contains("atlas")) {
      manifest.atlas = readAtlas(m.at("atlas"), manifestPath);
      manifest.header.heldBricks = manifest.atlas->bricks;
      if (!manifest.atlas->masks.empty()) manifest.header.heldMasks = manifest.atlas->masks;
    }
  } catch (const nlohmann::json::exception& e) {
    throw InputError(fmt::format("{}: {}", manifestPath, oneLine(e.what())));
  }
  if (!(manifest.scale > 0.0) || !std::isfinite(manifest.scale))
    throw InputError(fmt::format("{}: \"coefficient_scale\" must be a positive number", manifestPath));
  return manifest;
}

// Slice k's pixels into the volume's grids, every channel found by name.
void readSlice(const std::filesystem::path& dir, const Manifest& manifest, int k, const std::string& manifestPath,
               const std::vector<VolumeGrid>& grids, std::vector<float>& pixels, Volume& volume) {
  const std::vector<std::string>& slices = manifest.slices;
  const SliceLayout layout{manifest.header.grid, manifest.atlas ? &*manifest.atlas : nullptr};
  const double scale = manifest.scale;
  const std::string slicePath = (dir / slices[k]).string();
  const std::unique_ptr<ImageReader> image = openSlice(dir, slices[k], k, layout.texels(), manifestPath);
  const ImageHeader& spec = image->header();
  std::vector<std::pair<int, std::pair<const VolumeGrid*, int>>> sources;  // channel index → grid component
  for (const VolumeGrid& grid : grids)
    for (int c = 0; c < grid.components; ++c) {
      const std::string name = componentName(grid, c);
      const auto it = std::find(spec.channelNames.begin(), spec.channelNames.end(), name);
      if (it == spec.channelNames.end()) throw InputError(fmt::format("{}: channel '{}' is missing", slicePath, name));
      sources.push_back({int(it - spec.channelNames.begin()), {&grid, c}});
    }
  pixels.resize(std::size_t(spec.width) * spec.height * spec.channels);
  if (!image->readFloats(spec.channels, pixels.data()))
    throw InputError(fmt::format("{}: cannot read the pixels: {}", slicePath, image->error()));
  for (int j = 0; j < spec.height; ++j)
    for (int i = 0; i < spec.width; ++i) {
      const float* px = pixels.data() + (std::size_t(j) * spec.width + i) * spec.channels;
      const std::int64_t p = layout.probeAt(i, j, k);
      for (const auto& [channel, target] : sources) {
        const auto& [grid, c] = target;
        float value = px[channel];
        if (grid->kind == VolumeGrid::Kind::ProbeState) {
          if (!(value == 0.0f || value == 1.0f || value == 2.0f || value == 3.0f))
            throw InputError(fmt::format("{}: probe_state at ({}, {}) is {}; states are 0, 1, 2 or 3", slicePath, i, j, value));
        } else if (scaled(*grid)) {
          value = float(double(value) * scale);
        }
        // A part read as its own bricks only skips the others, which must be zero (Invalid) as the
        // part's writer left them; so must an atlas texel that holds no probe.
        if ((p < 0 || !setGridValue(volume, *grid, c, p, value)) && value != 0.0f)
          throw InputError(fmt::format("{}: texel ({}, {}) has {} = {}, {} (stored as zeros)", slicePath, i, j,
                                       componentName(*grid, c), value,
                                       p < 0            ? std::string("but holds no probe of the atlas")
                                       : volume.shard ? fmt::format("outside the bricks of its shard {}", shardName(*volume.shard))
                                                      : std::string("outside the bricks the volume holds")));
      }
    }
}

}  // namespace

namespace {

// The slice set in `dir` whose manifest is `m`.
Volume readSliceSet(const std::filesystem::path& dir, const nlohmann::json& m, const std::string& path,
                    PartReading parts) {
  const std::string manifestPath = (dir / kManifest).string();
  const Manifest manifest = readManifest(m, manifestPath);
  const SliceLayout layout{manifest.header.grid, manifest.atlas ? &*manifest.atlas : nullptr};
  const int depth = layout.texels().z();
  if (depth < 0 || manifest.slices.size() != std::size_t(depth))
    throw InputError(fmt::format("{}: {} slices listed for {} texels along z", manifestPath, manifest.slices.size(), depth));
  // Every slice is checked against the manifest before anything is allocated for it: the
  // manifest's sizes are only believed once the images agree with them.
  for (int k = 0; k < depth; ++k) openSlice(dir, manifest.slices[k], k, layout.texels(), manifestPath);
  Volume volume = manifest.header.emptyVolume(manifestPath, parts);

  const std::unique_ptr<Basis> basis = makeBasis(volume.basisName);
  const DistanceGrids distanceGrids = distanceGridsInFile(manifest.header.text);
  if (distanceGrids == DistanceGrids::Atlas)
    throw InputError(fmt::format("{}: {} has \"texel_grids\": \"atlas\", which only a .vdb holds: EXR slices hold "
                                 "\"rgb\"", manifestPath, kDistanceMapKey));
  const std::vector<VolumeGrid> grids =
      volumeGrids(*basis, volume.visibilityPerProbe, manifest.header.hasProbeStates, volume.distanceMap,
                  distanceGrids, volume.keepsSkyDirect, volume.keepsSkyBounced);
  std::vector<float> pixels;
  for (int k = 0; k < depth; ++k) readSlice(dir, manifest, k, manifestPath, grids, pixels, volume);
  requireFiniteValues(volume, path);
  return volume;
}

}  // namespace

std::vector<std::pair<std::string, std::string>> exrMetadataText(const nlohmann::json& metadata) {
  std::vector<std::pair<std::string, std::string>> text;
  for (const auto& [key, value] : metadata.items()) text.push_back({key, value.get<std::string>()});
  return text;
}

std::filesystem::path exrVolumeDirectory(const std::string& path) {
  std::filesystem::path dir = path;
  return dir.filename() == kManifest ? dir.parent_path() : dir;
}

Volume readExrSlices(const std::string& path, PartReading parts) {
  const std::filesystem::path dir = exrVolumeDirectory(path);
  const std::string manifestPath = (dir / kManifest).string();
  const nlohmann::json m = parseManifest(path, manifestPath);
  if (m.contains(kLevelsManifestKey))
    throw InputError(fmt::format("{}: an adaptive volume of {} levels; this command reads a uniform volume only "
                                 "(docs/ADAPTIVE.md says which commands read levels)",
                                 path, m[kLevelsManifestKey].size()));
  if (m.contains("atlas"))
    throw InputError(fmt::format("{}: one level of an adaptive volume; read the volume's directory, which holds "
                                 "every level", path));
  return readSliceSet(dir, m, path, parts);
}

nlohmann::json readExrManifest(const std::string& path) {
  const std::filesystem::path dir = exrVolumeDirectory(path);
  return parseManifest(path, (dir / kManifest).string());
}

Volume readAtlasSliceSet(const std::string& directory, const nlohmann::json& manifest) {
  if (!manifest.contains("atlas"))
    throw InputError(fmt::format("{}: \"atlas\" is missing (a level's bricks)",
                                 (std::filesystem::path(directory) / kManifest).string()));
  return readSliceSet(directory, manifest, directory, PartReading::EveryProbe);
}

}  // namespace baker
