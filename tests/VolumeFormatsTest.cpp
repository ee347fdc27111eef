#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <openvdb/openvdb.h>
#include <random>
#include <sstream>
#include <stdexcept>
#include <sys/resource.h>
#include <thread>
#include <tuple>

#include "basis/BasisRegistry.h"
#include "common/Error.h"
#include "common/Fnv1a64.h"
#include "formats/ExrSlices.h"
#include "formats/VdbChecksum.h"
#include "formats/VdbWriter.h"
#include "formats/VolumeLayout.h"
#include "formats/VolumeReader.h"
#include "formats/VolumeSampler.h"
#include "images/ImageFiles.h"
#include "tests/GltfTestAssets.h"
#include "tests/TestData.h"

// Volumes through both formats: what goes in comes out, and broken files say what is wrong.
namespace baker {
namespace {

// A volume of random values for `basis` over a grid that crosses brick boundaries unevenly.
Volume randomVolume(const Basis& basis, unsigned seed, Eigen::Vector3i dims = {9, 3, 10}) {
  std::mt19937 rng(seed);
  std::normal_distribution<float> normal(0.0f, 2.0f);
  Volume v;
  v.grid.dims = dims;
  v.grid.origin = Eigen::Vector3d(-1.25, 0.5, 3.0);
  v.grid.spacing = 0.375;
  v.basisName = basis.name();
  v.coefficientsPerProbe = basis.totalCoefficients();
  v.visibilityPerProbe = basis.functions(0).count();
  const std::size_t n = std::size_t(v.grid.probeCount());
  v.coefficients.resize(n * v.coefficientsPerProbe);
  for (float& c : v.coefficients) c = normal(rng);
  v.visibility.resize(n * v.visibilityPerProbe);
  for (float& c : v.visibility) c = normal(rng);
  v.states.resize(n);
  v.offsets.resize(n);
  for (std::size_t p = 0; p < n; ++p) {
    v.states[p] = ProbeState(p % 7 == 3 ? 2 : p % 11 == 5 ? 0 : 1);
    v.offsets[p] = Eigen::Vector3f::Zero();
    if (v.states[p] == ProbeState::Relocated) v.offsets[p] = 0.05f * Eigen::Vector3f(normal(rng), normal(rng), normal(rng));
  }
  v.settings["rays"] = "64";
  return v;
}

// randomVolume(basis, seed) with a distance map of `layout`, its values uniform in [0, 1).
Volume randomVolumeWithDistanceMap(const Basis& basis, unsigned seed, const DistanceMapLayout& layout) {
  Volume v = randomVolume(basis, seed, {9, 3, 10});
  v.distanceMap = layout;
  std::mt19937 rng(seed + 1);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  v.distanceMoments.resize(std::size_t(v.grid.probeCount() * v.distanceMomentsPerProbe()));
  for (float& m : v.distanceMoments) m = unit(rng);
  return v;
}

void expectSame(const Volume& a, const Volume& b, double relative, const std::string& what) {
  EXPECT_EQ(a.basisName, b.basisName) << what;
  EXPECT_EQ(a.grid.dims, b.grid.dims) << what;
  EXPECT_EQ(a.grid.origin, b.grid.origin) << what;
  EXPECT_EQ(a.grid.spacing, b.grid.spacing) << what;
  EXPECT_EQ(a.settings, b.settings) << what;
  ASSERT_EQ(a.coefficients.size(), b.coefficients.size()) << what;
  ASSERT_EQ(a.visibility.size(), b.visibility.size()) << what;
  for (std::size_t i = 0; i < a.coefficients.size(); ++i)
    ASSERT_NEAR(a.coefficients[i], b.coefficients[i], relative * std::abs(a.coefficients[i]) + (relative > 0 ? 1e-4 : 0))
        << what << " coefficient " << i;
  for (std::size_t i = 0; i < a.visibility.size(); ++i)
    ASSERT_NEAR(a.visibility[i], b.visibility[i], relative * std::abs(a.visibility[i]) + (relative > 0 ? 1e-4 : 0))
        << what << " visibility " << i;
  EXPECT_TRUE(a.states == b.states) << what;
  EXPECT_TRUE(a.offsets == b.offsets) << what << ": offsets are always stored in float";
}

TEST(VolumeFormats, EveryBasisRoundTripsThroughVdbAndExr) {
  const std::string dir = test::makeTempDir("formats_round_trip");
  unsigned seed = 1;
  for (const std::string& name : basisNames()) {
    const auto basis = makeBasis(name);
    const Volume v = randomVolume(*basis, seed++);
    writeVdb(v, *basis, dir + "/v.vdb");
    expectSame(v, readVolume(dir + "/v.vdb"), 0.0, name + " vdb");
    writeExrSlices(v, *basis, dir + "/float", ExrPrecision::Float);
    expectSame(v, readVolume(dir + "/float"), 0.0, name + " exr float");
    writeExrSlices(v, *basis, dir + "/half", ExrPrecision::Half);
    expectSame(v, readVolume(dir + "/half/manifest.json"), 1.0 / 2048.0, name + " exr half");
  }
}

// Brick (1,0,0) holds only Invalid probes but touches brick (0,0,0)'s valid ones: an engine blends
// them in the cells between, so it is stored. Brick (2,0,0) touches only Invalid probes: left out,
// it reads as zeros.
TEST(VolumeFormats, OnlyBricksAwayFromValidProbesAreLeftOut) {
  const std::string dir = test::makeTempDir("formats_sparse");
  const auto basis = makeBasis("sh-l1");
  Volume v = randomVolume(*basis, 7, {20, 4, 4});
  for (int k = 0; k < 4; ++k)
    for (int j = 0; j < 4; ++j)
      for (int i = 8; i < 20; ++i) v.states[v.grid.linearIndex(i, j, k)] = ProbeState::Invalid;
  writeVdb(v, *basis, dir + "/v.vdb");
  writeExrSlices(v, *basis, dir + "/exr", ExrPrecision::Float);
  for (const std::string& path : {dir + "/v.vdb", dir + "/exr"}) {
    const Volume r = readVolume(path);
    for (int k = 0; k < 4; ++k)
      for (int j = 0; j < 4; ++j)
        for (int i = 0; i < 20; ++i) {
          const std::int64_t p = v.grid.linearIndex(i, j, k);
          if (i < 16) {
            ASSERT_EQ(r.states[p], v.states[p]) << path;
            for (int c = 0; c < r.coefficientsPerProbe; ++c)
              ASSERT_EQ(r.coefficients[p * r.coefficientsPerProbe + c], v.coefficients[p * v.coefficientsPerProbe + c])
                  << path << " probe " << i << "," << j << "," << k;
            continue;
          }
          EXPECT_EQ(r.states[p], ProbeState::Invalid) << path;
          for (int c = 0; c < r.coefficientsPerProbe; ++c) ASSERT_EQ(r.coefficients[p * r.coefficientsPerProbe + c], 0.0f);
        }
  }
}

// Half stops at 65504: larger coefficients are divided by a power of two recorded in the header.
TEST(VolumeFormats, HalfSlicesScaleValuesBeyondTheHalfRange) {
  const std::string dir = test::makeTempDir("formats_half_scale");
  const auto basis = makeBasis("sh-l0");
  Volume v = randomVolume(*basis, 3, {2, 2, 2});
  v.coefficients[0] = 1.0e6f;
  v.coefficients[4] = -3.0e5f;
  writeExrSlices(v, *basis, dir + "/exr", ExrPrecision::Half);
  const nlohmann::json manifest = nlohmann::json::parse(std::ifstream(dir + "/exr/manifest.json"));
  EXPECT_EQ(manifest["coefficient_scale"].get<double>(), 16.0);  // 1e6 / 65504 = 15.3
  const Volume r = readVolume(dir + "/exr");
  EXPECT_NEAR(r.coefficients[0], 1.0e6f, 1.0e6f / 1024.0f);
  EXPECT_NEAR(r.coefficients[4], -3.0e5f, 3.0e5f / 1024.0f);
  for (float c : r.coefficients) EXPECT_TRUE(std::isfinite(c));
}

// At a probe the sample is that probe; between probes it is the trilinear mix, so E is too
// (reconstruction is linear in the coefficients); outside it clamps to the border.
TEST(VolumeFormats, SampleInterpolatesLikeA3dTexture) {
  const auto basis = makeBasis("ad-ycocg");
  const Volume v = randomVolume(*basis, 11, {3, 2, 2});
  const Eigen::Vector3d n = Eigen::Vector3d(0.3, -0.5, 0.8).normalized();
  auto probeE = [&](int i, int j, int k) { return basis->reconstruct(v.probe(v.grid.linearIndex(i, j, k)), n); };
  auto sampledE = [&](const Eigen::Vector3d& world) {
    const VolumeSample s = sampleVolume(v, world);
    return basis->reconstruct(s.coefficients.data(), n);
  };
  EXPECT_TRUE(sampledE(v.grid.position(1, 1, 0)).isApprox(probeE(1, 1, 0), 1e-6f));
  const Eigen::Vector3f mid = sampledE(0.5 * (v.grid.position(1, 0, 1) + v.grid.position(2, 0, 1)));
  EXPECT_TRUE(mid.isApprox(0.5f * (probeE(1, 0, 1) + probeE(2, 0, 1)), 1e-5f));
  const Eigen::Vector3d corner = v.grid.position(0, 0, 0) + v.grid.spacing * Eigen::Vector3d(0.25, 0.5, 0.75);
  Eigen::Vector3f expected = Eigen::Vector3f::Zero();
  for (int c = 0; c < 8; ++c) {
    const int i = c & 1, j = (c >> 1) & 1, k = c >> 2;
    expected += float((i ? 0.25 : 0.75) * (j ? 0.5 : 0.5) * (k ? 0.75 : 0.25)) * probeE(i, j, k);
  }
  EXPECT_TRUE(sampledE(corner).isApprox(expected, 1e-5f));
  EXPECT_TRUE(sampledE(v.grid.position(2, 1, 1) + Eigen::Vector3d(10, 10, 10)).isApprox(probeE(2, 1, 1), 1e-6f));
}

std::string fileBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

std::string errorOf(const std::string& path) {
  try {
    readVolume(path);
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(VolumeFormats, BrokenFilesAreNamedWithWhatIsWrong) {
  const std::string dir = test::makeTempDir("formats_broken");
  const auto basis = makeBasis("sh-l2");
  const Volume v = randomVolume(*basis, 5);
  writeVdb(v, *basis, dir + "/v.vdb");
  const auto size = std::filesystem::file_size(dir + "/v.vdb");
  std::filesystem::copy_file(dir + "/v.vdb", dir + "/cut.vdb");
  std::filesystem::resize_file(dir + "/cut.vdb", size / 2);
  EXPECT_NE(errorOf(dir + "/cut.vdb").find(dir + "/cut.vdb"), std::string::npos) << errorOf(dir + "/cut.vdb");
  std::ofstream(dir + "/junk.vdb") << "not a volume";
  EXPECT_NE(errorOf(dir + "/junk.vdb").find("not a readable OpenVDB volume"), std::string::npos);
  EXPECT_NE(errorOf(dir + "/none.vdb").find("does not exist"), std::string::npos);

  writeExrSlices(v, *basis, dir + "/exr", ExrPrecision::Half);
  std::filesystem::copy(dir + "/exr", dir + "/cut_exr");
  const std::string slice = dir + "/cut_exr/z0004.exr";
  std::filesystem::resize_file(slice, std::filesystem::file_size(slice) / 2);
  EXPECT_NE(errorOf(dir + "/cut_exr").find("z0004.exr"), std::string::npos) << errorOf(dir + "/cut_exr");
  std::filesystem::copy(dir + "/exr", dir + "/gap_exr");
  std::filesystem::remove(dir + "/gap_exr/z0002.exr");
  EXPECT_NE(errorOf(dir + "/gap_exr").find("z0002.exr: slice file is missing"), std::string::npos);
  std::filesystem::copy(dir + "/exr", dir + "/bad_manifest");
  std::ofstream(dir + "/bad_manifest/manifest.json") << "{\"format\": \"baker-exr-slices\", \"basis\": \"sh-l2\"}";
  EXPECT_NE(errorOf(dir + "/bad_manifest").find("manifest.json"), std::string::npos) << errorOf(dir + "/bad_manifest");
  std::filesystem::copy(dir + "/exr", dir + "/other_slice");
  std::filesystem::copy_file(dir + "/exr/z0000.exr", dir + "/other_slice/z0001.exr",
                             std::filesystem::copy_options::overwrite_existing);
  EXPECT_NE(errorOf(dir + "/other_slice").find("z0001.exr: holds slice 0, but the manifest lists it as slice 1"),
            std::string::npos)
      << errorOf(dir + "/other_slice");
}

// A write that fails part way (here: the process may not write more than 64 KiB to a file, as
// on a full disk) names the output and why, and leaves nothing behind, in either format.
TEST(VolumeFormats, AWriteThatFailsPartWayLeavesNothing) {
  const std::string dir = test::makeTempDir("formats_full");
  const auto basis = makeBasis("sh-l2");
  const Volume v = randomVolume(*basis, 21, {64, 64, 2});  // each EXR slice alone is over 64 KiB
  rlimit original{};
  ASSERT_EQ(getrlimit(RLIMIT_FSIZE, &original), 0);
  const auto previousHandler = std::signal(SIGXFSZ, SIG_IGN);  // EFBIG instead of the signal
  rlimit small = original;
  small.rlim_cur = 64 * 1024;
  ASSERT_EQ(setrlimit(RLIMIT_FSIZE, &small), 0);
  std::string vdbError = "(no error)", exrError = "(no error)";
  try {
    writeVdb(v, *basis, dir + "/v.vdb");
  } catch (const std::exception& e) {
    vdbError = e.what();
  }
  try {
    writeExrSlices(v, *basis, dir + "/exr", ExrPrecision::Float);
  } catch (const std::exception& e) {
    exrError = e.what();
  }
  setrlimit(RLIMIT_FSIZE, &original);
  std::signal(SIGXFSZ, previousHandler);
  EXPECT_NE(vdbError.find(dir + "/v.vdb"), std::string::npos) << vdbError;
  EXPECT_NE(vdbError.find(std::strerror(EFBIG)), std::string::npos) << vdbError;
  EXPECT_NE(exrError.find(dir + "/exr"), std::string::npos) << exrError;
  std::vector<std::string> left;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) left.push_back(entry.path().filename().string());
  EXPECT_TRUE(left.empty()) << "left behind: " << left.front();
}

// OpenVDB trusts the sizes a file claims: one flipped byte could crash it or make it allocate
// gigabytes. Every byte is covered by the checksum the writer seals in, checked first.
TEST(VolumeFormats, AnyChangedByteOfAVdbIsCaughtByItsChecksum) {
  const std::string dir = test::makeTempDir("formats_checksum");
  const auto basis = makeBasis("sh-l1");
  writeVdb(randomVolume(*basis, 3), *basis, dir + "/v.vdb");
  const std::string bytes = fileBytes(dir + "/v.vdb");
  ASSERT_NE(bytes.find(kVdbChecksumKey), std::string::npos);
  EXPECT_EQ(bytes.find(kVdbChecksumPlaceholder), std::string::npos) << "the placeholder was not sealed";
  const std::size_t step = std::max<std::size_t>(1, bytes.size() / 300);
  for (std::size_t at = 0; at < bytes.size(); at += step) {
    std::string changed = bytes;
    changed[at] = char(changed[at] ^ 0x10);
    std::ofstream(dir + "/changed.vdb", std::ios::binary) << changed;
    const std::string error = errorOf(dir + "/changed.vdb");
    ASSERT_NE(error.find(dir + "/changed.vdb: not a readable OpenVDB volume"), std::string::npos) << at << ": " << error;
  }
  // A valid OpenVDB file without the checksum (another tool's, or an older baker's) is refused.
  openvdb::initialize();
  openvdb::io::File(dir + "/plain.vdb").write({openvdb::FloatGrid::create()});
  EXPECT_NE(errorOf(dir + "/plain.vdb").find("has no 'baker.content_xxh64' metadata"), std::string::npos)
      << errorOf(dir + "/plain.vdb");
}

// A manifest's sizes are believed only once the slices agree: a claim of 16384² probes is
// refused by the first slice's size, before anything is allocated for it.
TEST(VolumeFormats, ExrManifestSizesAreCheckedAgainstTheSlicesFirst) {
  const std::string dir = test::makeTempDir("formats_manifest");
  const auto basis = makeBasis("sh-l1");
  writeExrSlices(randomVolume(*basis, 4, {2, 2, 1}), *basis, dir + "/exr", ExrPrecision::Half);
  nlohmann::json manifest = nlohmann::json::parse(std::ifstream(dir + "/exr/manifest.json"));
  const nlohmann::json original = manifest;
  manifest["dims"] = {16384, 16384, 1};
  std::ofstream(dir + "/exr/manifest.json") << manifest.dump();
  EXPECT_NE(errorOf(dir + "/exr").find("z0000.exr: 2 × 2 pixels, expected 16384 × 16384"), std::string::npos)
      << errorOf(dir + "/exr");

  manifest = original;
  manifest["metadata"]["baker.format_version"] = "99";
  std::ofstream(dir + "/exr/manifest.json") << manifest.dump();
  EXPECT_NE(errorOf(dir + "/exr").find("baker.format_version is 99: written by a newer baker"), std::string::npos)
      << errorOf(dir + "/exr");
  manifest["metadata"].erase("baker.format_version");
  std::ofstream(dir + "/exr/manifest.json") << manifest.dump();
  EXPECT_NE(errorOf(dir + "/exr").find("baker.format_version is missing"), std::string::npos) << errorOf(dir + "/exr");
}

// The files are ordinary OpenVDB and OpenEXR: the standard tools read them.
TEST(VolumeFormats, StandardToolsReadTheFiles) {
  const std::string dir = test::makeTempDir("formats_tools");
  const auto basis = makeBasis("ad-ycocg");
  const Volume v = randomVolume(*basis, 9);
  writeVdb(v, *basis, dir + "/v.vdb");
  writeExrSlices(v, *basis, dir + "/exr", ExrPrecision::Half);
  if (std::system("command -v vdb_print > /dev/null") != 0 || std::system("command -v exrheader > /dev/null") != 0)
    GTEST_SKIP() << "vdb_print or exrheader is not installed (Debian libopenvdb-tools, openexr)";
  EXPECT_EQ(std::system(("vdb_print -l '" + dir + "/v.vdb' > '" + dir + "/vdb.txt' 2>&1").c_str()), 0);
  EXPECT_EQ(std::system(("exrheader '" + dir + "/exr/z0000.exr' > '" + dir + "/exr.txt' 2>&1").c_str()), 0);
  std::stringstream vdb, exr;
  vdb << std::ifstream(dir + "/vdb.txt").rdbuf();
  exr << std::ifstream(dir + "/exr.txt").rdbuf();
  EXPECT_NE(vdb.str().find("Y_00"), std::string::npos) << vdb.str();
  EXPECT_NE(vdb.str().find("baker.basis"), std::string::npos);
  EXPECT_NE(exr.str().find("Co_11"), std::string::npos) << exr.str();
  EXPECT_NE(exr.str().find("baker.basis"), std::string::npos);
}

// A .vdb file's bytes with the `file_delayed_load` metadata that OpenVDB 10's writer adds to every
// grid taken out, and each grid record's metadata count and stream positions mended to match.
// Walks the file as OpenVDB's Archive writes it: a 57-byte header (magic, three version words, a
// flag, a 36-character UUID), the file's metadata, the grid count, then per grid its name, type
// and instance parent, three stream positions (where its data starts, where its buffers start,
// where it ends), its compression word and its metadata. Throws if the file ends early.
std::string withoutDelayedLoadMetadata(const std::string& file) {
  std::size_t at = 57;
  const auto within = [&](std::size_t end) {
    if (end > file.size()) throw std::runtime_error(fmt::format("the file ends at {}, before byte {}", file.size(), end));
  };
  const auto u32 = [&] {
    within(at + 4);
    std::uint32_t v = 0;
    std::memcpy(&v, file.data() + at, sizeof v);
    at += sizeof v;
    return v;
  };
  const auto string = [&] {
    const std::uint32_t n = u32();
    within(at + n);
    at += n;
    return file.substr(at - n, n);
  };
  const auto metadataEntry = [&] {  // its name, the type and value skipped
    std::string name = string();
    string();
    at += u32();
    return name;
  };
  for (std::uint32_t n = u32(); n > 0; --n) metadataEntry();
  const std::uint32_t gridCount = u32();
  std::string out = file.substr(0, at);
  std::int64_t moved = 0;  // by what was taken out of the records before
  for (std::uint32_t g = 0; g < gridCount; ++g) {
    const std::size_t recordAt = at;
    for (int s = 0; s < 3; ++s) string();
    std::int64_t positions[3];
    within(at + sizeof positions);
    std::memcpy(positions, file.data() + at, sizeof positions);
    within(std::size_t(positions[2]));
    EXPECT_EQ(std::int64_t(at + sizeof positions), positions[0]) << "grid " << g;
    out += file.substr(recordAt, at - recordAt);
    at = std::size_t(positions[0]) + 4;
    const std::size_t countAt = at;
    std::uint32_t count = u32();
    std::size_t entryAt = 0, entryEnd = 0;
    for (std::uint32_t m = 0; m < count; ++m) {
      const std::size_t start = at;
      if (metadataEntry() == openvdb::GridBase::META_FILE_DELAYED_LOAD) entryAt = start, entryEnd = at;
    }
    EXPECT_NE(entryEnd, 0u) << "grid " << g << " has no file_delayed_load metadata";
    const std::int64_t taken = std::int64_t(entryEnd - entryAt);
    const std::int64_t mended[3] = {positions[0] + moved, positions[1] + moved - taken, positions[2] + moved - taken};
    out.append(reinterpret_cast<const char*>(mended), sizeof mended);
    --count;
    out += file.substr(std::size_t(positions[0]), 4);
    out.append(reinterpret_cast<const char*>(&count), sizeof count);
    out += file.substr(countAt + 4, entryAt - countAt - 4);
    out += file.substr(entryEnd, std::size_t(positions[2]) - entryEnd);
    moved -= taken;
    at = std::size_t(positions[2]);
  }
  EXPECT_EQ(at, file.size());
  return out;
}

// The writer builds and writes sixteen grids at a time through OpenVDB's Archive, to bound
// memory, and the distance atlas straight into the file. Its file must be byte for byte the one
// OpenVDB's own all-at-once writer makes from the same grids and metadata, but for the UUID every
// OpenVDB file carries and the delayed-load metadata OpenVDB adds to every grid (see writeRecord
// in VdbWriter.cpp).
TEST(VolumeFormats, VdbWrittenGridByGridIsWhatOpenVdbWrites) {
  const std::string dir = test::makeTempDir("formats_grid_by_grid");
  const auto basis = makeBasis("sh-l2");
  Volume v = randomVolume(*basis, 13, {17, 9, 8});
  v.distanceMap = DistanceMapLayout::baked(2, 0.5);
  std::mt19937 rng(14);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  v.distanceMoments.resize(std::size_t(v.grid.probeCount() * v.distanceMomentsPerProbe()));
  for (float& m : v.distanceMoments) m = unit(rng);
  writeVdb(v, *basis, dir + "/ours.vdb");
  openvdb::initialize();
  openvdb::io::File ours(dir + "/ours.vdb");
  ours.open(/*delayLoad=*/false);
  const openvdb::MetaMap::Ptr metadata = ours.getMetadata();
  const std::string ourUuid = ours.getUniqueTag();
  // In the file's order, which is the layout's (getGrids would sort them by name).
  openvdb::GridPtrVec grids;
  for (const VolumeGrid& spec : volumeGrids(*basis, v, VolumeFile::OpenVdb)) grids.push_back(ours.readGrid(spec.name));
  ours.close();
  ASSERT_EQ(grids.size(), 21u);  // sh-l2's 9 × 2, sky visibility, probe states, the atlas
  openvdb::io::File theirs(dir + "/theirs.vdb");
  theirs.write(grids, *metadata);
  const std::string theirUuid = theirs.getUniqueTag();  // set when its header was written

  const auto bytesWithoutUuid = [](const std::string& path, const std::string& uuid) {
    std::string s = fileBytes(path);
    const std::size_t at = s.find(uuid);
    EXPECT_NE(at, std::string::npos) << path << " does not hold its UUID " << uuid;
    if (at != std::string::npos) s.replace(at, uuid.size(), uuid.size(), '-');
    return s;
  };
  const std::string a = bytesWithoutUuid(dir + "/ours.vdb", ourUuid);
  const std::string b = withoutDelayedLoadMetadata(bytesWithoutUuid(dir + "/theirs.vdb", theirUuid));
  const std::size_t common = std::min(a.size(), b.size());
  EXPECT_TRUE(a == b) << "sizes " << a.size() << " and " << b.size() << ", first difference at byte "
                      << std::distance(a.begin(), std::mismatch(a.begin(), a.begin() + common, b.begin()).first);
}

// Files of format 6 and older carry the FNV-1a hash of their bytes under the legacy key, sealed as
// the writers of then did: the 16 digits of the placeholder replaced by the hash of the file
// holding them as '0'.
void sealWithFnv1a(const std::string& path) {
  std::string bytes = fileBytes(path);
  const std::size_t key = bytes.find(kVdbLegacyChecksumKey);
  ASSERT_NE(key, std::string::npos) << path;
  const std::size_t digits = bytes.find(kVdbChecksumPlaceholder, key);
  ASSERT_NE(digits, std::string::npos) << path;
  Fnv1a64 hash;
  hash.add(bytes.data(), bytes.size());
  bytes.replace(digits, 16, fmt::format("{:016x}", hash.value()));
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
}

// A .vdb holds the distance map as one atlas grid (format 7), EXR slices as one RGB grid per texel
// (format 6); .vdb files of format 6, and of format 3 (a scalar grid per value), still read. All
// give back the map's floats exactly.
TEST(VolumeFormats, DistanceMapsReadFromEitherLayout) {
  const std::string dir = test::makeTempDir("formats_distance_layouts");
  const auto basis = makeBasis("sh-l1");
  const int n = 4, texels = n * n;
  const Volume v = randomVolumeWithDistanceMap(*basis, 21, DistanceMapLayout::baked(n, 0.9375));
  writeVdb(v, *basis, dir + "/new.vdb");
  writeExrSlices(v, *basis, dir + "/exr", ExrPrecision::Float);
  for (const std::string& path : {dir + "/new.vdb", dir + "/exr"}) {
    const Volume back = readVolume(path);
    EXPECT_TRUE(back.distanceMoments == v.distanceMoments) << path;
    EXPECT_EQ(back.distanceMap.size, n) << path;
    EXPECT_TRUE(back.distanceMap.skyVisibility) << path;
  }

  // The atlas as FORMAT.md lays it out: texel t = u + n·v of probe (i, j, k) at voxel
  // (i·n + u, j·n + v, k), R, G, B its values 2t, 2t + 1 and 2n² + t, voxels n times finer in x, y.
  openvdb::initialize();
  openvdb::io::File file(dir + "/new.vdb");
  file.open(/*delayLoad=*/false);
  openvdb::MetaMap metadata = *file.getMetadata();
  EXPECT_EQ(metadata.metaValue<std::string>("baker.format_version"), "7");
  nlohmann::json map = nlohmann::json::parse(metadata.metaValue<std::string>("baker.distance_map"));
  EXPECT_EQ(map.at("texel_grids"), "atlas");
  const auto atlas = openvdb::gridPtrCast<openvdb::Vec3SGrid>(file.readGrid("distance_map"));
  ASSERT_TRUE(atlas);
  EXPECT_EQ(atlas->activeVoxelCount(), openvdb::Index64(v.grid.probeCount() * texels));
  const openvdb::Vec3d voxel = atlas->transform().voxelSize();
  EXPECT_NEAR(voxel.x(), v.grid.spacing / n, 1e-12);
  EXPECT_NEAR(voxel.y(), v.grid.spacing / n, 1e-12);
  EXPECT_NEAR(voxel.z(), v.grid.spacing, 1e-12);
  const std::int64_t perProbe = v.distanceMomentsPerProbe();
  for (auto it = atlas->cbeginValueOn(); it; ++it) {
    const openvdb::Coord c = it.getCoord();
    const int i = c.x() / n, j = c.y() / n, t = c.x() % n + n * (c.y() % n);
    const float* m = v.distanceMoments.data() + v.grid.linearIndex(i, j, c.z()) * perProbe;
    ASSERT_EQ((*it)[0], m[2 * t]) << c;
    ASSERT_EQ((*it)[1], m[2 * t + 1]) << c;
    ASSERT_EQ((*it)[2], m[2 * texels + t]) << c;
  }

  // The same volume as the files of then: the atlas cut into an RGB grid per texel (format 6), or
  // into scalar grids per value (format 3), each sealed with FNV-1a.
  openvdb::GridPtrVec others, rgbGrids, scalarGrids(std::size_t(3 * texels));
  std::vector<openvdb::Vec3SGrid::Ptr> perTexel;
  for (int t = 0; t < texels; ++t) {
    perTexel.push_back(openvdb::Vec3SGrid::create(openvdb::Vec3s(0.0f)));
    perTexel.back()->setName(fmt::format("distance_map_{:03}", t));
  }
  for (auto it = atlas->cbeginValueOn(); it; ++it) {
    const openvdb::Coord c = it.getCoord();
    perTexel[std::size_t(c.x() % n + n * (c.y() % n))]->tree().setValue({c.x() / n, c.y() / n, c.z()}, *it);
  }
  const openvdb::GridPtrVecPtr written = file.getGrids();
  for (const openvdb::GridBase::Ptr& grid : *written)
    if (grid->getName() != "distance_map") others.push_back(grid);
  file.close();
  for (int t = 0; t < texels; ++t) {
    perTexel[std::size_t(t)]->setTransform(others.front()->transform().copy());
    rgbGrids.push_back(perTexel[std::size_t(t)]);
    for (int c = 0; c < 3; ++c) {
      auto scalar = openvdb::FloatGrid::create(0.0f);
      scalar->setTransform(others.front()->transform().copy());
      for (auto voxel = perTexel[std::size_t(t)]->cbeginValueOn(); voxel; ++voxel)
        scalar->tree().setValue(voxel.getCoord(), (*voxel)[c]);
      const int value = c < 2 ? 2 * t + c : 2 * texels + t;
      scalar->setName(c < 2 ? fmt::format("distance_moments_{:03}", value) : fmt::format("sky_visibility_map_{:03}", t));
      scalarGrids[std::size_t(value)] = scalar;
    }
  }
  // The grids of `distanceGrids` under `metadata` with baker.distance_map `description` and format `version`.
  const auto writeWith = [&](const std::string& name, const openvdb::GridPtrVec& distanceGrids,
                             const nlohmann::json& description, const std::string& version) {
    openvdb::GridPtrVec grids = others;
    grids.insert(grids.end(), distanceGrids.begin(), distanceGrids.end());
    metadata.removeMeta("baker.distance_map");
    metadata.insertMeta("baker.distance_map", openvdb::StringMetadata(description.dump()));
    metadata.removeMeta("baker.format_version");
    metadata.insertMeta("baker.format_version", openvdb::StringMetadata(version));
    metadata.removeMeta(kVdbChecksumKey);
    metadata.insertMeta(kVdbLegacyChecksumKey, openvdb::StringMetadata(kVdbChecksumPlaceholder));
    openvdb::io::File(dir + "/" + name).write(grids, metadata);
    sealWithFnv1a(dir + "/" + name);
    return dir + "/" + name;
  };
  nlohmann::json rgb = map, then = map;
  rgb["texel_grids"] = "rgb";
  then.erase("texel_grids");
  const std::string format6 = writeWith("format6.vdb", rgbGrids, rgb, "6");
  const std::string format3 = writeWith("format3.vdb", scalarGrids, then, "3");
  for (const std::string& path : {format6, format3}) {
    const Volume back = readVolume(path);
    EXPECT_TRUE(back.distanceMoments == v.distanceMoments) << path;
    expectSame(v, back, 0.0, path);
  }
  EXPECT_EQ(distanceGridsOf(format3), DistanceGrids::ScalarPerValue) << "what `baker inspect` names the grids by";
  EXPECT_EQ(distanceGridsOf(format6), DistanceGrids::RgbPerTexel);
  EXPECT_EQ(distanceGridsOf(dir + "/new.vdb"), DistanceGrids::Atlas);
  EXPECT_EQ(distanceGridsOf(dir + "/exr"), DistanceGrids::RgbPerTexel);

  // The key and the version must agree, and the key name a form this reader knows.
  nlohmann::json unknown = map, noSky = rgb;
  unknown["texel_grids"] = "tiles";
  noSky["sky_visibility"] = false;
  for (const auto& [name, grids, description, version, expected] :
       {std::tuple{"unknown.vdb", rgbGrids, unknown, "6", "\"texel_grids\" is \"tiles\""},
        std::tuple{"without_sky.vdb", rgbGrids, noSky, "6", "\"texel_grids\" is \"rgb\"; this reader knows \"rgb\" and"},
        std::tuple{"early_key.vdb", rgbGrids, rgb, "3", "\"texel_grids\": \"rgb\" in a file of format 3; it came with format 6"},
        std::tuple{"early_atlas.vdb", rgbGrids, map, "6", "\"texel_grids\": \"atlas\" in a file of format 6; it came with format 7"},
        std::tuple{"lost_key.vdb", scalarGrids, then, "6", "has no \"texel_grids\""}}) {
    const std::string error = errorOf(writeWith(name, grids, description, version));
    EXPECT_NE(error.find(expected), std::string::npos) << name << ": " << error;
  }
  // An atlas voxel outside the probes' maps is refused, naming the grid.
  {
    auto beyond = atlas->deepCopy();
    beyond->tree().setValue({v.grid.dims.x() * n, 0, 0}, openvdb::Vec3s(0.5f));
    metadata.removeMeta(kVdbLegacyChecksumKey);
    metadata.removeMeta("baker.distance_map");
    metadata.insertMeta("baker.distance_map", openvdb::StringMetadata(map.dump()));
    metadata.removeMeta("baker.format_version");
    metadata.insertMeta("baker.format_version", openvdb::StringMetadata("7"));
    metadata.insertMeta(kVdbChecksumKey, openvdb::StringMetadata(kVdbChecksumPlaceholder));
    openvdb::GridPtrVec grids = others;
    grids.push_back(beyond);
    openvdb::io::File(dir + "/beyond.vdb").write(grids, metadata);
    sealVdbChecksum(dir + "/beyond.vdb", std::filesystem::file_size(dir + "/beyond.vdb"));
    const std::string error = errorOf(dir + "/beyond.vdb");
    EXPECT_NE(error.find("grid 'distance_map' has a voxel at (36, 0, 0), outside the atlas"), std::string::npos) << error;
  }
}

// A map without the sky's shares (one read from a volume baked before relighting) is written as
// then: a scalar grid per value, format 3, no "texel_grids".
TEST(VolumeFormats, DistanceMapsWithoutTheSkysShareKeepFormat3) {
  const std::string dir = test::makeTempDir("formats_distance_no_sky");
  const auto basis = makeBasis("sh-l1");
  const Volume v = randomVolumeWithDistanceMap(*basis, 23, DistanceMapLayout{4, 0.9375, /*skyVisibility=*/false});
  writeVdb(v, *basis, dir + "/v.vdb");
  openvdb::initialize();
  openvdb::io::File file(dir + "/v.vdb");
  file.open(/*delayLoad=*/false);
  EXPECT_EQ(file.getMetadata()->metaValue<std::string>("baker.format_version"), "3");
  EXPECT_FALSE(nlohmann::json::parse(file.getMetadata()->metaValue<std::string>("baker.distance_map")).contains("texel_grids"));
  EXPECT_TRUE(file.hasGrid("distance_moments_031"));
  EXPECT_FALSE(file.hasGrid("distance_map_000"));
  file.close();
  EXPECT_TRUE(readVolume(dir + "/v.vdb").distanceMoments == v.distanceMoments);
}

// EXR slices written between relighting and format 6 held the sky's share of each texel as a
// scalar channel beside the moments'. The slices of today cut back into those channels, under
// format 3, read back to the same volume; the same channels under format 6 are refused.
TEST(VolumeFormats, Format3ExrSlicesWithTheSkysShareRead) {
  const std::string dir = test::makeTempDir("formats_exr_format3_sky");
  const auto basis = makeBasis("sh-l1");
  const Volume v = randomVolumeWithDistanceMap(*basis, 25, DistanceMapLayout::baked(4, 0.9375));
  writeExrSlices(v, *basis, dir + "/today", ExrPrecision::Float);

  // distance_map_TTT.R, .G, .B (values 2t, 2t + 1, 2n² + t) as distance_moments_{2t},
  // distance_moments_{2t + 1} and sky_visibility_map_{t}.
  const auto format3Name = [&](const std::string& name) {
    if (name.rfind("distance_map_", 0) != 0) return name;
    const int t = std::stoi(name.substr(13, 3));
    const char c = name.back();
    return c == 'B' ? fmt::format("sky_visibility_map_{:03}", t) : fmt::format("distance_moments_{:03}", 2 * t + (c == 'G'));
  };
  const auto writeThen = [&](const std::string& name, const std::string& version) {
    const std::string out = dir + "/" + name;
    std::filesystem::create_directories(out);
    nlohmann::json manifest = nlohmann::json::parse(std::ifstream(dir + "/today/manifest.json"));
    nlohmann::json map = nlohmann::json::parse(manifest["metadata"]["baker.distance_map"].get<std::string>());
    map.erase("texel_grids");
    manifest["metadata"]["baker.distance_map"] = map.dump();
    manifest["metadata"]["baker.format_version"] = version;
    manifest["format_version"] = std::stoi(version);
    std::vector<std::string> channels;
    for (const std::string& c : manifest["channels"].get<std::vector<std::string>>()) channels.push_back(format3Name(c));
    manifest["channels"] = channels;
    for (const std::string& slice : manifest["slices"].get<std::vector<std::string>>()) {
      ImageReader reader(dir + "/today/" + slice);
      const ImageHeader& h = reader.header();
      std::vector<float> pixels(std::size_t(h.width) * h.height * h.channels);
      EXPECT_TRUE(reader.readFloats(h.channels, pixels.data())) << reader.error();
      ImageToWrite image;
      image.format = "openexr";
      image.width = h.width;
      image.height = h.height;
      for (const std::string& c : h.channelNames) image.channelNames.push_back(format3Name(c));
      image.pixels = pixels.data();
      image.intAttributes = {{"baker.slice", reader.intAttribute("baker.slice", -1)}};
      std::string error;
      EXPECT_TRUE(writeImage(image, out + "/" + slice, &error)) << error;
    }
    std::ofstream(out + "/manifest.json") << manifest.dump(2) << "\n";
    return out;
  };
  const std::string format3 = writeThen("format3", "3");
  const Volume back = readVolume(format3);
  EXPECT_TRUE(back.distanceMap.skyVisibility);
  EXPECT_TRUE(back.distanceMoments == v.distanceMoments);
  expectSame(v, back, 0.0, format3);
  EXPECT_EQ(distanceGridsOf(format3), DistanceGrids::ScalarPerValue);
  const std::string error = errorOf(writeThen("format6", "6"));
  EXPECT_NE(error.find("texel_grids"), std::string::npos) << error;
}

// OpenVDB writes a random UUID into each header; ours is derived from the content, so the same
// volume written twice is the same file, and another volume gets another UUID.
TEST(VolumeFormats, TheSameVolumeIsTheSameVdbFile) {
  const std::string dir = test::makeTempDir("formats_same_file");
  const auto basis = makeBasis("sh-l2");
  const Volume volume = randomVolume(*basis, 13, {9, 9, 9});
  writeVdb(volume, *basis, dir + "/a.vdb");
  writeVdb(volume, *basis, dir + "/b.vdb");
  EXPECT_TRUE(fileBytes(dir + "/a.vdb") == fileBytes(dir + "/b.vdb"));
  writeVdb(randomVolume(*basis, 14, {9, 9, 9}), *basis, dir + "/c.vdb");
  openvdb::initialize();
  std::string tags[2];
  for (int i = 0; i < 2; ++i) {
    openvdb::io::File file(dir + (i == 0 ? "/a.vdb" : "/c.vdb"));
    file.open(false);
    tags[i] = file.getUniqueTag();
    file.close();
  }
  EXPECT_EQ(tags[0].size(), 36u);
  EXPECT_EQ(tags[0][14], '8') << tags[0] << ": an RFC 9562 version-8 UUID";
  EXPECT_NE(tags[0], tags[1]);
  EXPECT_NO_THROW(readVolume(dir + "/a.vdb")) << "the checksum covers the derived UUID";
}

// EXR slices carry no time of writing (OpenImageIO would stamp capDate): written twice, the
// same volume is the same bytes, slice by slice.
TEST(VolumeFormats, TheSameVolumeIsTheSameExrSlices) {
  const std::string dir = test::makeTempDir("formats_same_exr");
  const auto basis = makeBasis("ad-ycocg");
  const Volume volume = randomVolume(*basis, 15, {5, 4, 3});
  writeExrSlices(volume, *basis, dir + "/a", ExrPrecision::Half);
  std::this_thread::sleep_for(std::chrono::milliseconds(1100));  // a clock in the file would now differ
  writeExrSlices(volume, *basis, dir + "/b", ExrPrecision::Half);
  int slices = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir + "/a")) {
    const std::string name = entry.path().filename().string();
    EXPECT_TRUE(fileBytes(entry.path().string()) == fileBytes(dir + "/b/" + name)) << name;
    slices += entry.path().extension() == ".exr";
  }
  EXPECT_EQ(slices, 3);
}

// dir/panel.gltf: an emissive 2 m square.
void writePanel(const std::string& dir) {
  test::GltfBuilder gltf;
  const int emitter = gltf.material({{"emissiveFactor", {1.0, 0.5, 0.25}}, {"doubleSided", true}});
  gltf.node({{"mesh", test::squareMesh(gltf, 2.0f, emitter)}});
  gltf.write(dir, "panel");
}

// The whole file, through the command: one thread or two, the same bytes (default quality, so
// that probes stop at different rounds).
TEST(VolumeFormats, BakesOnAnyThreadCountWriteTheSameFile) {
  const std::string dir = test::makeTempDir("formats_same_bake");
  writePanel(dir);
  for (const char* threads : {"1", "2"}) {
    const test::ProcessResult bake = test::runBaker(
        dir, std::string("panel.gltf --spacing 0.7 --quality draft --threads ") + threads + " --out t" + threads + ".vdb");
    ASSERT_EQ(bake.exitCode, 0) << bake.err;
  }
  EXPECT_TRUE(fileBytes(dir + "/t1.vdb") == fileBytes(dir + "/t2.vdb"));
}

// A bake written as EXR slices, then `inspect` and `sample` on it, as a user would.
TEST(VolumeFormats, InspectAndSampleReadEitherFormat) {
  const std::string dir = test::makeTempDir("formats_cli");
  writePanel(dir);
  for (const std::string& out : {std::string("panel_exr"), std::string("panel.vdb")}) {
    const test::ProcessResult bake = test::runBaker(dir, "panel.gltf --spacing 0.5 --rays 64 --basis ad-srbf --out " + out);
    ASSERT_EQ(bake.exitCode, 0) << bake.err;
    const test::ProcessResult inspect = test::runBaker(dir, "inspect " + out + " --json");
    ASSERT_EQ(inspect.exitCode, 0) << inspect.err;
    const nlohmann::json info = nlohmann::json::parse(inspect.out);
    EXPECT_EQ(info["basis"], "ad-srbf");
    EXPECT_EQ(info["format"], out == "panel.vdb" ? "vdb" : "exr");
    EXPECT_GT(info["bytes"].get<std::int64_t>(), 0);
    EXPECT_EQ(info["probes"].get<std::int64_t>(), info["dims"][0].get<int>() * info["dims"][1].get<int>() * info["dims"][2].get<int>());
    EXPECT_EQ(info["grids"][0]["name"], "rgb_00");

    const test::ProcessResult sample = test::runBaker(dir, "sample " + out + " --at 1,1,0.3 --normal 0,0,-1 --json");
    ASSERT_EQ(sample.exitCode, 0) << sample.err;
    const nlohmann::json s = nlohmann::json::parse(sample.out);
    const Volume volume = readVolume(dir + "/" + out);
    const auto basis = basisOf(volume);
    const VolumeSample expected = sampleVolume(volume, {1, 1, 0.3});
    const Eigen::Vector3f e = basis->reconstruct(expected.coefficients.data(), Eigen::Vector3d(0, 0, -1));
    for (int c = 0; c < 3; ++c) EXPECT_FLOAT_EQ(s["irradiance"][c].get<float>(), e[c]) << out;
    EXPECT_GT(e.x(), 0.0f) << "the panel below lights a normal facing it";
  }
  const test::ProcessResult missing = test::runBaker(dir, "sample nothing.vdb --at 0,0,0 --normal 0,1,0");
  EXPECT_EQ(missing.exitCode, 2);
  EXPECT_NE(missing.err.find("nothing.vdb: volume file does not exist"), std::string::npos) << missing.err;
  const test::ProcessResult zero = test::runBaker(dir, "sample panel.vdb --at 0,0,0 --normal 0,0,0");
  EXPECT_EQ(zero.exitCode, 2);
}

}  // namespace
}  // namespace baker
