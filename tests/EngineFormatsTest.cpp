#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>

#include "basis/BasisRegistry.h"
#include "basis/SphericalHarmonics.h"
#include "common/Error.h"
#include "formats/BevyIrradianceVolume.h"
#include "formats/Ktx2File.h"
#include "formats/Rgb9e5.h"
#include "formats/ThreeJsProbeGrid.h"
#include "formats/VolumeReader.h"
#include "formats/VolumeWriter.h"
#include "tests/BakerProcess.h"
#include "tests/TestData.h"
#include "tests/VolumeFiles.h"

// The engines' formats: the texel encodings against their specifications, what goes in comes
// back out through the one reader, and damaged exports name their file. tests/engines/ reads the
// same files with the engines' own code.
namespace baker {
namespace {

// A volume of `basis` whose irradiance is positive everywhere (a constant plus a gentle lobe per
// probe, drawn from `seed`): what an engine's unsigned texels can hold.
Volume positiveVolume(const Basis& basis, unsigned seed, const Eigen::Vector3i& dims = {5, 3, 9}) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> uniform(-1.0f, 1.0f);
  Volume v;
  v.grid.dims = dims;
  v.grid.origin = Eigen::Vector3d(-1.25, 0.5, 3.0);
  v.grid.spacing = 0.375;
  v.basisName = basis.name();
  v.coefficientsPerProbe = basis.totalCoefficients();
  v.coefficients.assign(std::size_t(v.grid.probeCount()) * v.coefficientsPerProbe, 0.0f);
  for (std::int64_t p = 0; p < v.grid.probeCount(); ++p)
    for (int c = 0; c < 3; ++c) {
      const SphericalFunctions& f = basis.functions(c);
      // SH: a constant and a small lobe; other bases: every function's weight near a level.
      const Eigen::Vector3d axis = Eigen::Vector3d(uniform(rng), uniform(rng), uniform(rng)).normalized();
      std::vector<double> values(f.count());
      f.evaluate(axis, values.data());
      const float level = 2.0f + uniform(rng);
      for (int i = 0; i < f.count(); ++i)
        v.coefficients[p * v.coefficientsPerProbe + basis.coefficientOffset(c) + i] =
            basis.family() == "sh"                           ? (i == 0 ? level * 3.5449077f : 0.3f * float(values[i]))
            : basis.colorSpace() == ColorSpace::YCoCg && c > 0 ? 0.05f * float(values[i])  // a little chroma
                                                               : level + 0.5f * float(values[i]);
    }
  v.settings["rays"] = "64";
  for (const auto& [name, value] : parameterSettings(basis.parameters())) v.settings[name] = value;
  return v;
}

TEST(Rgb9e5, EncodesOneAsTheSpecificationDoes) {
  // 1.0: mantissa 256 with exponent 16 (the Data Format Specification's sampleUpper 8448 = 0x2100).
  const Rgb9e5Packing one = packRgb9e5({1.0f, 1.0f, 1.0f});
  EXPECT_EQ(one.bits, 256u | 256u << 9 | 256u << 18 | 16u << 27);
  EXPECT_EQ(unpackRgb9e5(one.bits), Eigen::Vector3f(1, 1, 1));
  EXPECT_EQ(one.clamped, 0);
  const Rgb9e5Packing largest = packRgb9e5({kRgb9e5Max, 0.0f, 0.5f});
  EXPECT_EQ(largest.bits & 0x1ffu, 511u);
  EXPECT_EQ(largest.bits >> 27, 31u);
  EXPECT_EQ(unpackRgb9e5(largest.bits).x(), kRgb9e5Max);
}

TEST(Rgb9e5, ClampsAndCountsWhatItCannotHold) {
  const Rgb9e5Packing p = packRgb9e5({-0.25f, 1e6f, std::nanf("")});
  EXPECT_EQ(p.clamped, 3);
  const Eigen::Vector3f back = unpackRgb9e5(p.bits);
  EXPECT_EQ(back.x(), 0.0f);
  EXPECT_EQ(back.y(), kRgb9e5Max);
  EXPECT_EQ(back.z(), 0.0f);
}

TEST(Rgb9e5, RoundsEachChannelToHalfAStepOfTheSharedExponent) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> logUniform(-20.0f, 15.9f);
  for (int n = 0; n < 20000; ++n) {
    const Eigen::Vector3f v(std::exp2(logUniform(rng)), std::exp2(logUniform(rng)), std::exp2(logUniform(rng)));
    const Rgb9e5Packing p = packRgb9e5(v);
    const double step = std::exp2(int(p.bits >> 27) - 24);
    const Eigen::Vector3f back = unpackRgb9e5(p.bits);
    for (int c = 0; c < 3; ++c) ASSERT_LE(std::abs(double(back[c]) - v[c]), 0.5 * step * (1 + 1e-9)) << v.transpose();
    // The exponent is the smallest that holds the largest channel in nine bits.
    ASSERT_LT(v.maxCoeff(), 512.0 * step);
    if ((p.bits >> 27) > 0) ASSERT_GE(v.maxCoeff(), 255.5 * step) << v.transpose();
  }
  // A mantissa that rounds up to 512 moves to the next exponent.
  const Rgb9e5Packing up = packRgb9e5({511.9f, 0.0f, 0.0f});
  EXPECT_EQ(unpackRgb9e5(up.bits).x(), 512.0f);
}

TEST(Ktx2File, RoundTripsAndRefusesWhatLiesOutsideTheFile) {
  Ktx2Texture3D t;
  t.vkFormat = kVkFormatE5B9G9R9;
  t.typeSize = 4;
  t.width = 3;
  t.height = 4;
  t.depth = 6;
  t.dataFormatDescriptor = rgb9e5DataFormatDescriptor();
  t.keyValues = {{"KTXwriter", "baker test"}};
  for (std::uint32_t i = 0; i < 3 * 4 * 6 * 4; ++i) t.texels.push_back(std::uint8_t(i * 7));
  const std::vector<std::uint8_t> bytes = encodeKtx2(t);
  ASSERT_EQ(t.dataFormatDescriptor.size() * 4, 124u);  // the spec's total size for RGB9E5
  const Ktx2Texture3D back = decodeKtx2(bytes, "t.ktx2");
  EXPECT_EQ(back.vkFormat, t.vkFormat);
  EXPECT_EQ(back.width, 3u);
  EXPECT_EQ(back.height, 4u);
  EXPECT_EQ(back.depth, 6u);
  EXPECT_EQ(back.dataFormatDescriptor, t.dataFormatDescriptor);
  EXPECT_EQ(back.keyValues, t.keyValues);
  EXPECT_EQ(back.texels, t.texels);
  // Level data aligned to 4 bytes, after the header, the one level's entry, the DFD and the KVD.
  const std::uint64_t levelOffset = bytes[80] | bytes[81] << 8;
  EXPECT_EQ(levelOffset % 4, 0u);
  EXPECT_EQ(bytes.size(), levelOffset + t.texels.size());
  for (std::size_t length : {std::size_t(0), std::size_t(11), std::size_t(90), std::size_t(200), bytes.size() - 1}) {
    const std::vector<std::uint8_t> cut(bytes.begin(), bytes.begin() + std::ptrdiff_t(length));
    try {
      decodeKtx2(cut, "cut.ktx2");
      ADD_FAILURE() << "a file cut to " << length << " bytes was read";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("cut.ktx2"), std::string::npos) << e.what();
    }
  }
}

TEST(ThreeJsProbeGrid, UsesThreeJsSphericalHarmonicsConvention) {
  // three.js's SphericalHarmonics3 and its shaders (r187), function by function.
  const SphericalHarmonics sh(2);
  std::mt19937 rng(3);
  std::normal_distribution<double> normal;
  for (int n = 0; n < 100; ++n) {
    const Eigen::Vector3d d = Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized();
    const double x = d.x(), y = d.y(), z = d.z();
    const double three[9] = {0.282095,         0.488603 * y,     0.488603 * z, 0.488603 * x, 1.092548 * x * y,
                             1.092548 * y * z, 0.315392 * (3 * z * z - 1), 1.092548 * x * z, 0.546274 * (x * x - y * y)};
    double ours[9];
    sh.evaluate(d, ours);
    for (int i = 0; i < 9; ++i) ASSERT_NEAR(ours[i], three[i], 2e-6) << "function " << i;
  }
}

TEST(ThreeJsProbeGrid, ReadsBackWhatItWrote) {
  const std::string dir = test::makeTempDir("threejs_round_trip");
  for (const char* name : {"sh-l2", "sh-l1"}) {
    const auto basis = makeBasis(name);
    const Volume v = positiveVolume(*basis, 11);
    const std::string out = dir + "/" + name;
    const EngineExport report = writeVolume(v, *basis, {out, VolumeFormat::ThreeJs});
    EXPECT_EQ(report.clampedValues, 0);
    EXPECT_EQ(volumeFormatOf(out), "threejs");
    const Volume back = readVolume(out + "/light_probe_grid.json");
    EXPECT_EQ(back.basisName, "sh-l2");
    EXPECT_EQ(back.grid.dims, v.grid.dims);
    EXPECT_NEAR(back.grid.spacing, v.grid.spacing, 1e-12);
    EXPECT_LT((back.grid.origin - v.grid.origin).norm(), 1e-12);
    EXPECT_EQ(back.settings.at("rays"), "64");
    const int count = basis->coefficientCount(0);
    for (std::int64_t p = 0; p < v.grid.probeCount(); ++p)
      for (int c = 0; c < 3; ++c)
        for (int k = 0; k < 9; ++k) {
          const float written = k < count ? v.probe(p)[c * count + k] : 0.0f;
          ASSERT_NEAR(back.probe(p)[c * 9 + k], written, 4e-7 * 11.0) << name << " probe " << p << " function " << k;
        }
  }
}

TEST(ThreeJsProbeGrid, RefusesBasesItCannotHoldExactly) {
  for (const std::string& name : basisNames()) {
    const auto basis = makeBasis(name);
    const bool holds = name == "sh-l0" || name == "sh-l1" || name == "sh-l2";
    if (holds) {
      EXPECT_NO_THROW(requireWritable({"x", VolumeFormat::ThreeJs}, *basis)) << name;
      continue;
    }
    try {
      requireWritable({"x", VolumeFormat::ThreeJs}, *basis);
      ADD_FAILURE() << name << " was taken";
    } catch (const SettingError& e) {
      EXPECT_EQ(e.setting(), "basis");
      EXPECT_NE(e.problem().find(name), std::string::npos) << e.what();
      EXPECT_NE(e.problem().find("sh-l2"), std::string::npos) << e.what();
      EXPECT_NE(e.problem().find("bevy"), std::string::npos) << e.what();
    }
    EXPECT_NO_THROW(requireWritable({"x", VolumeFormat::Bevy}, *basis)) << name;
  }
}

TEST(BevyIrradianceVolume, ReadsBackAsTheAmbientCubeBevyShadesWith) {
  const std::string dir = test::makeTempDir("bevy_round_trip");
  for (const char* name : {"ambient-cube", "sh-l2", "ad-ycocg", "sg-12"}) {
    const auto basis = makeBasis(name);
    const Volume v = positiveVolume(*basis, 5);
    const std::string out = dir + "/" + name;
    const EngineExport report = writeVolume(v, *basis, {out, VolumeFormat::Bevy});
    EXPECT_EQ(report.clampedValues, 0) << name;
    EXPECT_EQ(volumeFormatOf(out + "/irradiance_volume.ktx2"), "bevy");
    const Volume back = readVolume(out);
    const auto cube = basisOf(back);  // the bake's basis parameters are not the ambient cube's
    EXPECT_EQ(back.basisName, "ambient-cube");
    EXPECT_EQ(back.settings.at("source_basis"), name);
    EXPECT_EQ(back.grid.dims, v.grid.dims);
    EXPECT_LT((back.grid.origin - v.grid.origin).norm(), 1e-12);
    for (std::int64_t p = 0; p < v.grid.probeCount(); ++p)
      for (int face = 0; face < 6; ++face) {
        Eigen::Vector3d n = Eigen::Vector3d::Zero();
        n[face / 2] = face % 2 ? -1.0 : 1.0;
        const Eigen::Vector3f written = basis->reconstruct(v.probe(p), n), read = cube->reconstruct(back.probe(p), n);
        // RGB9E5 keeps each channel to 1/512 of the texel's largest (here after dividing by π).
        for (int c = 0; c < 3; ++c)
          ASSERT_NEAR(read[c], written[c], written.maxCoeff() / 511.0) << name << " probe " << p << " face " << face;
      }
  }
}

// Damaged exports: one file each, the message naming it and the reader refusing before it reads on.
TEST(EngineFormats, DamagedExportsNameTheirFile) {
  const std::string dir = test::makeTempDir("engine_damage");
  const auto cube = makeBasis("ambient-cube");
  const auto sh = makeBasis("sh-l2");
  const Volume v = positiveVolume(*cube, 1), w = positiveVolume(*sh, 1);
  const auto damaged = [&](const std::string& name, const std::string& file, const std::function<void(nlohmann::json&)>& edit,
                           const std::string& expected) {
    const std::string out = dir + "/" + name;
    if (file == "irradiance_volume.json") writeVolume(v, *cube, {out, VolumeFormat::Bevy});
    else writeVolume(w, *sh, {out, VolumeFormat::ThreeJs});
    const std::string path = out + "/" + file;
    nlohmann::json j = nlohmann::json::parse(std::ifstream(path));
    edit(j);
    std::ofstream(path) << j.dump();
    try {
      readVolume(out);
      ADD_FAILURE() << name << " was read";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(out + "/"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(file), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
    }
  };
  damaged("bevy_no_scale", "irradiance_volume.json", [](nlohmann::json& j) { j["transform"].erase("scale"); }, "scale");
  damaged("bevy_resolution", "irradiance_volume.json",
          [](nlohmann::json& j) {
            j["resolution"][0] = 6;
            j["transform"]["scale"][0] = 6 * 0.375;
          },
          "texels");
  damaged("bevy_huge", "irradiance_volume.json", [](nlohmann::json& j) { j["resolution"] = {100000, 100000, 100000}; },
          "resolution");
  damaged("bevy_rotated", "irradiance_volume.json", [](nlohmann::json& j) { j["transform"]["rotation"] = {0, 1, 0, 0}; },
          "rotation");
  damaged("bevy_fraction", "irradiance_volume.json", [](nlohmann::json& j) { j["resolution"][1] = 2.5; }, "whole numbers");
  damaged("bevy_beyond_int", "irradiance_volume.json", [](nlohmann::json& j) { j["resolution"][1] = 1e20; },
          "whole numbers");
  damaged("bevy_intensity", "irradiance_volume.json", [](nlohmann::json& j) { j["intensity"] = 1e308; }, "non-finite");
  damaged("three_data", "light_probe_grid.json", [](nlohmann::json& j) { j["coefficients"]["data"].erase(0); }, "27 per probe");
  damaged("three_type", "light_probe_grid.json", [](nlohmann::json& j) { j["metadata"]["type"] = "Mesh"; }, "LightProbeGrid");
  damaged("three_cells", "light_probe_grid.json", [](nlohmann::json& j) { j["width"] = 1.0; }, "cubic cells");
  // A truncated texture and a missing atlas: the file that is wrong is named.
  const std::string cut = dir + "/bevy_cut";
  writeVolume(v, *cube, {cut, VolumeFormat::Bevy});
  std::filesystem::resize_file(cut + "/irradiance_volume.ktx2", 300);
  EXPECT_THROW(
      try { readVolume(cut); } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("irradiance_volume.ktx2"), std::string::npos) << e.what();
        throw;
      },
      InputError);
  const std::string noAtlas = dir + "/three_no_atlas";
  writeVolume(w, *sh, {noAtlas, VolumeFormat::ThreeJs});
  std::filesystem::remove(noAtlas + "/light_probe_grid.bin");
  EXPECT_THROW(readVolume(noAtlas), InputError);
}

TEST(EngineFormats, TheSameVolumeIsTheSameFiles) {
  const std::string dir = test::makeTempDir("engine_same");
  const auto sh = makeBasis("sh-l2");
  const Volume v = positiveVolume(*sh, 4);
  for (const auto& [format, files] :
       {std::pair{VolumeFormat::Bevy, std::vector<std::string>{"irradiance_volume.ktx2", "irradiance_volume.json"}},
        std::pair{VolumeFormat::ThreeJs, std::vector<std::string>{"light_probe_grid.json", "light_probe_grid.bin"}}}) {
    writeVolume(v, *sh, {dir + "/a", format});
    writeVolume(v, *sh, {dir + "/b", format});
    for (const std::string& file : files) {
      const std::string a = test::bytesOf(dir + "/a/" + file);
      EXPECT_FALSE(a.empty()) << file;
      EXPECT_EQ(a, test::bytesOf(dir + "/b/" + file)) << file;
    }
    std::filesystem::remove_all(dir + "/a");
    std::filesystem::remove_all(dir + "/b");
  }
}

TEST(EngineFormats, OutputsReplaceOnlyTheirOwnKind) {
  const std::string dir = test::makeTempDir("engine_outputs");
  const auto sh = makeBasis("sh-l2");
  const Volume w = positiveVolume(*sh, 2);
  const std::string three = dir + "/room_threejs";
  writeVolume(w, *sh, {three, VolumeFormat::ThreeJs});
  EXPECT_EQ(volumeOutput("room.gltf", three, "threejs", "half").path, three);  // rebaking replaces it
  EXPECT_THROW(volumeOutput("room.gltf", three, "bevy", "half"), InputError);  // not a Bevy export
  EXPECT_EQ(volumeOutput(dir + "/room.gltf", "", "bevy", "half").path, "room_bevy");
  EXPECT_EQ(volumeOutput(dir + "/room.gltf", "", "threejs", "half").path, "room_threejs");
  EXPECT_THROW(volumeOutput("room.gltf", dir + "/x.vdb", "bevy", "half"), SettingError);
  EXPECT_EQ(preferredBasis(volumeOutput("room.gltf", "", "bevy", "half")), "ambient-cube");
  EXPECT_TRUE(prefersNonNegativeFit({"x", VolumeFormat::Bevy}, *makeBasis("ambient-cube")));
  EXPECT_FALSE(prefersNonNegativeFit({"x", VolumeFormat::Bevy}, *sh));
  EXPECT_FALSE(prefersNonNegativeFit({"x", VolumeFormat::Vdb}, *makeBasis("ambient-cube")));
}

TEST(EngineFormats, InspectReadsEngineExportsAndRefusesForeignDirectories) {
  const std::string dir = test::makeTempDir("engine_inspect");
  const std::string scene = test::sourcePath("data/default_room/default_room.gltf");
  const test::ProcessResult bevy =
      test::runBaker(dir, {scene, "--format", "bevy", "--rays", "16", "--spacing", "2", "--out", "room_bevy", "--quiet"});
  ASSERT_EQ(bevy.exitCode, 0) << bevy.err;
  const test::ProcessResult inspect = test::runBaker(dir, {"inspect", "room_bevy", "--json"});
  ASSERT_EQ(inspect.exitCode, 0) << inspect.err;
  const nlohmann::json j = nlohmann::json::parse(inspect.out);
  EXPECT_EQ(j["format"], "bevy");
  EXPECT_EQ(j["basis"], "ambient-cube");
  EXPECT_EQ(j["settings"]["non_negative"], "true");
  std::filesystem::create_directory(dir + "/empty");
  const test::ProcessResult foreign = test::runBaker(dir, std::vector<std::string>{"inspect", "empty"});
  EXPECT_EQ(foreign.exitCode, 2);
  EXPECT_NE(foreign.err.find("empty"), std::string::npos) << foreign.err;
}

}  // namespace
}  // namespace baker
