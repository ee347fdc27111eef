#pragma once
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "basis/Basis.h"
#include "formats/BrickAtlas.h"
#include "formats/VolumeHeader.h"
#include "volume/Volume.h"

namespace baker {

enum class ExrPrecision { Half, Float };

// A volume as EXR slices: a directory holding one multi-channel OpenEXR image per z slice
// (z0000.exr, …; pixel column i, row j = probe (i, j, k), row 0 first in the file) and
// manifest.json, which lists the slices and repeats the header. Slices rather than one
// multi-part file: each is an ordinary RGB-and-more image every EXR tool reads, and a slice is
// what an engine uploads as one layer of a 3D texture. Channels are named after the grids of
// volumeGrids ("rgb_00.R", "Y_03", "visibility_00", "probe_state", "probe_offset.X", …).
// Coefficients and visibility are stored in `precision`; probe states and offsets always in
// float. Half has no values above 65504: when a coefficient exceeds it, every coefficient is
// divided by a power of two, recorded as baker.coefficient_scale (multiply to decode).
// Nothing appears at `directory` on failure.
void writeExrSlices(const Volume& volume, const Basis& basis, const std::string& directory, ExrPrecision precision);

// Reads a directory written by writeExrSlices (or its manifest.json). InputError naming the
// file and what is missing or inconsistent.
Volume readExrSlices(const std::string& path, PartReading parts = PartReading::EveryProbe);

// Whether `path` is a directory with a manifest.json of EXR slices.
bool isExrSliceDirectory(const std::string& path);
// Whether it is one this tool wrote (its manifest's "format" says so): what a writer may replace.
bool replaceableExrDirectory(const std::string& path);

// Every EXR manifest's "format".
constexpr const char* kExrFormatName = "baker-exr-slices";

// What the levels of an adaptive volume are made of (ExrLevels.h). The manifest key of an
// adaptive volume's directory listing its levels' directories.
constexpr const char* kLevelsManifestKey = "levels";
// Writes `volume`'s slice set into the existing `directory`: its probes where `atlas` packs its
// bricks (null: slice k is z = k, the bricks a file keeps), `extra` added to its manifest.
void writeSliceSet(const Volume& volume, const Basis& basis, const std::string& directory, ExrPrecision precision,
                   const BrickAtlas* atlas, const nlohmann::json& extra);
// The directory of the EXR volume at `path` (the directory, or its manifest.json).
std::filesystem::path exrVolumeDirectory(const std::string& path);
// The manifest of the EXR volume at `path` (a directory or its manifest.json), parsed only.
nlohmann::json readExrManifest(const std::string& path);
// A manifest's "metadata" object as the text entries every format's header holds
// (nlohmann::json::type_error for a value that is not a string).
std::vector<std::pair<std::string, std::string>> exrMetadataText(const nlohmann::json& metadata);
// Reads the slice set of one level in `directory`, whose parsed manifest.json is `manifest`: its
// bricks as the manifest's atlas lists them.
Volume readAtlasSliceSet(const std::string& directory, const nlohmann::json& manifest);

}  // namespace baker
