#include "relight/Relighting.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <algorithm>
#include <chrono>
#include <optional>
#include <utility>

#include "bake/SkyProjection.h"
#include "basis/StoredSignal.h"
#include "common/Error.h"
#include "common/Timing.h"
#include "formats/VolumeReader.h"
#include "volume/InvalidProbeFill.h"
#include "volume/SkyTransfer.h"

namespace baker {
namespace {

constexpr double kConcentratedSolidAngle = 0.01, kConcentratedShare = 0.25;
// How much of the level's mean flux is added to a probe's own before their ratio scales its light
// off surfaces: a probe that sees little sky takes the level's ratio, one that sees much its own.
// Measured on the report's scenes, 1 and 0.1 are within 0-5 points of the level of each other
// (docs/RELIGHTING.md).
constexpr double kLevelShare = 1.0;

std::string setting(const Volume& volume, const std::string& key, const std::string& fallback) {
  const auto it = volume.settings.find(key);
  return it == volume.settings.end() ? fallback : it->second;
}

bool simulated(const Volume& volume, const std::string& effect) {
  return setting(volume, "effect." + effect, "off") == "on";
}

// A count the bake recorded (0 when it recorded none); InputError naming the key when it is not one.
int countSetting(const Volume& volume, const std::string& key, const std::string& name) {
  const std::string text = setting(volume, key, "0");
  try {
    std::size_t used = 0;
    const int count = std::stoi(text, &used);
    if (used == text.size() && count >= 0) return count;
  } catch (const std::exception&) {
  }
  throw InputError(fmt::format("{}: baker.setting.{} \"{}\" is not a count", name, key, text));
}

// The share of the sky's flux in its brightest 0.01 sr (the studio light of studio_small_03 holds
// most of its flux in 0.0074 sr): light that relighting through a probe's blurred visibility cannot
// take away or add where its shadows' edges are.
double concentratedShare(const SkyRadiance& sky) {
  struct Texel {
    double radiance, solidAngle;
  };
  std::vector<Texel> texels;
  double total = 0.0;
  for (int row = 0; row < sky.height; ++row) {
    const double solidAngle = latLongSolidAngle(1.0 / sky.width, double(row) / sky.height, double(row + 1) / sky.height);
    for (int column = 0; column < sky.width; ++column) {
      const double radiance = sky.texel(column, row).mean();
      texels.push_back({radiance, solidAngle});
      total += radiance * solidAngle;
    }
  }
  if (!(total > 0.0)) return 0.0;
  std::sort(texels.begin(), texels.end(), [](const Texel& a, const Texel& b) { return a.radiance > b.radiance; });
  double flux = 0.0, solidAngle = 0.0;
  for (const Texel& t : texels) {
    if (solidAngle >= kConcentratedSolidAngle) break;
    flux += t.radiance * t.solidAngle;
    solidAngle += t.solidAngle;
  }
  return flux / total;
}

// The stored visibility `transfer` reads, of the probe in `row`.
Eigen::VectorXd visibilityOf(const Volume& level, const SkyTransfer& transfer, std::int64_t row) {
  if (!transfer.readsMap())
    return Eigen::Map<const Eigen::VectorXf>(level.visibility.data() + row * level.visibilityPerProbe,
                                             level.visibilityPerProbe)
        .cast<double>();
  const int texels = level.distanceMap.texels();
  return Eigen::Map<const Eigen::VectorXf>(
             level.distanceMoments.data() + row * level.distanceMomentsPerProbe() + 2 * texels, texels)
      .cast<double>();
}

// How much of each sky a probe sees directly, per RGB channel: ∫ V(ω) L(ω) dω through its map
// (SkyTransfer::mapFlux). The light the sky sends off surfaces is scaled by the ratio new / old:
// the surfaces around a probe see about the sky it sees (through the same window, under the same
// open sky).
struct SkyFlux {
  Eigen::Matrix3Xd before, after;
  // Per channel, the flux of the old sky and of the new one the map `v` lets through.
  std::pair<Eigen::Vector3d, Eigen::Vector3d> seen(const Eigen::VectorXd& v) const { return {before * v, after * v}; }
};

// Per probe row of `level`, the factor its light off surfaces takes, per RGB channel: the ratio of
// the new sky's flux through its map to the old one's, with kLevelShare times the level's mean
// over the probes baked in place or moved (not those filled from neighbours) added, so that a
// probe that sees no sky takes the level's ratio. The ratios of relightings A → B → C multiply to
// A → C's: each one's numerator is the next one's denominator. For a basis in YCoCg, whose chroma
// has functions of its own, one factor for all three: the luminance's.
std::vector<Eigen::Vector3d> bounceScales(const Volume& level, const SkyTransfer& transfer, const SkyFlux& flux,
                                          ColorSpace space) {
  const std::int64_t rows = level.rows.count(level.grid);
  std::vector<std::pair<Eigen::Vector3d, Eigen::Vector3d>> seen(static_cast<std::size_t>(rows));
  tbb::parallel_for(std::int64_t(0), rows, [&](std::int64_t row) {
    seen[std::size_t(row)] = flux.seen(visibilityOf(level, transfer, row));
  });
  Eigen::Vector3d meanOld = Eigen::Vector3d::Zero(), meanNew = Eigen::Vector3d::Zero();
  std::int64_t baked = 0;
  for (std::int64_t row = 0; row < rows; ++row) {
    if (!level.states.empty() && level.states[std::size_t(row)] == ProbeState::Invalid) continue;
    meanOld += seen[std::size_t(row)].first;
    meanNew += seen[std::size_t(row)].second;
    ++baked;
  }
  if (baked > 0) {
    meanOld /= double(baked);
    meanNew /= double(baked);
  }
  std::vector<Eigen::Vector3d> scales(static_cast<std::size_t>(rows), Eigen::Vector3d::Ones());
  const Eigen::Vector3d luminance(0.25, 0.5, 0.25);
  for (std::int64_t row = 0; row < rows; ++row) {
    const Eigen::Vector3d old = seen[std::size_t(row)].first + kLevelShare * meanOld;
    const Eigen::Vector3d now = seen[std::size_t(row)].second + kLevelShare * meanNew;
    Eigen::Vector3d& scale = scales[std::size_t(row)];
    if (space == ColorSpace::YCoCg) {
      const double before = luminance.dot(old);
      scale.setConstant(before > 0.0 ? luminance.dot(now) / before : 1.0);
    } else {
      for (int c = 0; c < 3; ++c) scale[c] = old[c] > 0.0 ? now[c] / old[c] : 1.0;
    }
  }
  return scales;
}

// With the level's directly seen sky kept apart (Volume::skyDirect), `operators` take a black sky
// to the new one: that part is replaced by what they give. Without it they take the old sky to
// the new one, and their result is added. With the sky's light off surfaces kept apart too
// (Volume::skyBounced) and `bounce` scales, that part is scaled by them.
void relightLevel(Volume& level, const SkyTransfer& transfer, const std::vector<Eigen::MatrixXd>& operators,
                  const std::vector<Eigen::Vector3d>* bounce, const Basis& basis, const std::string& name) {
  const std::int64_t rows = level.rows.count(level.grid);
  std::atomic<bool> finite{true};
  tbb::parallel_for(std::int64_t(0), rows, [&](std::int64_t row) {
    const Eigen::VectorXd v = visibilityOf(level, transfer, row);
    const std::int64_t first = row * level.coefficientsPerProbe;
    float* coefficients = level.coefficients.data() + first;
    float* skyDirect = level.keepsSkyDirect ? level.skyDirect.data() + first : nullptr;
    float* skyBounced = bounce && level.keepsSkyBounced ? level.skyBounced.data() + first : nullptr;
    for (int c = 0; c < 3; ++c) {
      const int offset = basis.coefficientOffset(c), count = basis.coefficientCount(c);
      Eigen::Map<Eigen::VectorXf> channel(coefficients + offset, count);
      const Eigen::VectorXd added = operators[std::size_t(c)] * v;
      Eigen::VectorXd relit = channel.cast<double>() + added;
      if (skyDirect) {
        Eigen::Map<Eigen::VectorXf> seen(skyDirect + offset, count);
        relit -= seen.cast<double>();
        seen = added.cast<float>();
        if (!seen.allFinite()) finite = false;
      }
      if (skyBounced) {
        Eigen::Map<Eigen::VectorXf> offSurfaces(skyBounced + offset, count);
        const Eigen::VectorXd scaled = offSurfaces.cast<double>() * (*bounce)[std::size_t(row)][c];
        relit += scaled - offSurfaces.cast<double>();
        offSurfaces = scaled.cast<float>();
        if (!offSurfaces.allFinite()) finite = false;
      }
      channel = relit.cast<float>();
      if (!channel.allFinite()) finite = false;
    }
  });
  if (!finite)
    throw NumericalError(fmt::format("{}: relit values leave single precision; is the new sky's intensity sensible?", name));
  // Probes inside geometry hold their neighbours' light, as the bake filled them; their maps are
  // zeros, so they take their relit neighbours' again. A shard's part leaves that to the merge.
  if (transfer.readsMap() && !level.shard && !level.states.empty()) {
    fillInvalidProbes(level.grid, level.rows, level.states, level.coefficientsPerProbe, level.coefficients);
    fillInvalidProbes(level.grid, level.rows, level.states, level.skyDirectPerProbe(), level.skyDirect);
    fillInvalidProbes(level.grid, level.rows, level.states, level.skyBouncedPerProbe(), level.skyBounced);
  }
}

bool keepsSkyDirect(const AdaptiveVolume& volume) {
  return std::all_of(volume.levels.begin(), volume.levels.end(), [](const Volume& v) { return v.keepsSkyDirect; });
}

bool keepsSkyBounced(const AdaptiveVolume& volume) {
  return std::all_of(volume.levels.begin(), volume.levels.end(), [](const Volume& v) { return v.keepsSkyBounced; });
}

}  // namespace

SkyChange relightVolume(AdaptiveVolume& volume, const Basis& basis, const SkyRadiance& sky,
                        const std::string& description, const std::string& name) {
  Volume& first = volume.levels.front();
  if (first.visibilityPerProbe == 0 && !first.distanceMap.skyVisibility)
    throw InputError(fmt::format("{}: holds no sky visibility, which relighting reads (an engine's export keeps none: "
                                 "relight the .vdb or EXR slices baker wrote, then export)", name));
  if (!first.sky)
    throw InputError(fmt::format("{}: records no sky (baker.sky), so the sky it was baked under cannot be taken away; "
                                 "bake it again with this version to relight it", name));
  if (setting(first, "non_negative", "false") == "true")
    throw InputError(fmt::format("{}: was fitted with non-negative coefficients (baker.setting.non_negative), which a "
                                 "relit volume would not keep; bake it with non_negative off to relight it", name));
  // The same sky changes nothing, to the bit (adding an exact 0 would turn a stored -0 into +0).
  if (first.sky->rgb == sky.rgb) {
    if (!first.settings.count("baked_sky")) first.settings["baked_sky"] = setting(first, "sky", "none");
    first.settings["sky"] = description;
    return {"unchanged: the new sky is the one the volume holds", "nothing to take away: the same sky", false};
  }
  const StoredSignal signal = storedSignalOf(first.settings);
  // Every level reads V the same way: adaptive levels hold no maps.
  const SkyTransfer transfer(basis, signal, BandWindow{countSetting(first, "window", name)},
                             volume.levels.size() == 1 ? first.distanceMap : DistanceMapLayout{0, 0.0});
  const bool exact = keepsSkyDirect(volume);
  const std::vector<Eigen::MatrixXd> operators = transfer.operators(exact ? SkyRadiance{} : *first.sky, sky);
  // The light off surfaces is scaled by what each probe's map sees of both skies; without maps
  // (adaptive levels, --distance-map 0) it is kept as baked.
  const bool scalesBounce = exact && transfer.readsMap() && keepsSkyBounced(volume);
  if (scalesBounce && first.shard)
    throw InputError(fmt::format("{}: is a shard's part; its light off surfaces is scaled by the whole bake's mean "
                                 "view of the sky, so merge the parts first and relight the merged volume",
                                 name));
  std::optional<SkyFlux> flux;
  if (scalesBounce) flux = SkyFlux{transfer.mapFlux(*first.sky), transfer.mapFlux(sky)};
  for (Volume& level : volume.levels) {
    if (!exact) {
      level.keepsSkyDirect = false;
      level.skyDirect.clear();
    }
    if (!exact || !scalesBounce) {
      level.keepsSkyBounced = false;
      level.skyBounced.clear();
    }
    std::vector<Eigen::Vector3d> bounce;
    if (scalesBounce) bounce = bounceScales(level, transfer, *flux, basis.colorSpace());
    relightLevel(level, transfer, operators, scalesBounce ? &bounce : nullptr, basis, name);
  }
  if (!first.settings.count("baked_sky")) first.settings["baked_sky"] = setting(first, "sky", "none");
  first.settings["sky"] = description;
  first.sky = sky;
  return {transfer.visibilitySource(),
          exact ? "exactly: each probe's directly seen sky as baked (grids sky_direct_*)"
                : "through the stored visibility, as the new sky is added (the volume keeps no sky_direct grids)",
          scalesBounce};
}

DescribedSkyHarmonics skyHarmonicsOf(const SceneOptions& options, std::vector<std::string>& warnings) {
  const Environment environment = environmentFromOptions(options, warnings);
  return {SkyHarmonics::of(recordSky(environment)), skyDescription(environment)};
}

RelightReport relightVolumeFile(const RelightRequest& request) {
  if (request.sky.environmentMap.empty() && request.sky.sky.empty())
    throw SettingError("env", "is needed: relighting takes a new sky, an environment map or a constant sky");
  const auto start = std::chrono::steady_clock::now();
  RelightReport report;
  const Environment environment = environmentFromOptions(request.sky, report.warnings);
  AdaptiveVolume volume = readLevels(request.volumePath);
  const std::unique_ptr<Basis> basis = basisOf(volume.coarsest());
  requireLevelsWritable(request.output, int(volume.levels.size()));
  const Volume& first = volume.coarsest();
  report.basis = basis->name();
  report.signal = storedSignalName(storedSignalOf(first.settings));
  report.levels = int(volume.levels.size());
  for (const Volume& level : volume.levels) report.probes += level.rows.count(level.grid);
  report.fromSky = setting(first, "sky", "none");
  report.bounces = countSetting(first, "bounces", request.volumePath);
  report.otherLights = simulated(first, "punctual_lights") || simulated(first, "direct_punctual") ||
                       simulated(first, "emission") || simulated(first, "emissive_lights");
  const SkyRadiance newSky = recordSky(environment);
  const std::string newSkyDescription = skyDescription(environment);
  // The old sky goes through the visibility too unless the volume keeps its directly seen part.
  std::vector<std::pair<std::string, std::optional<SkyRadiance>>> seenThroughVisibility = {{newSkyDescription, newSky}};
  if (!keepsSkyDirect(volume)) seenThroughVisibility.push_back({report.fromSky, first.sky});
  for (const auto& [which, sky] : seenThroughVisibility) {
    const double share = sky ? concentratedShare(*sky) : 0.0;
    if (share > kConcentratedShare)
      report.warnings.push_back(fmt::format("{} holds {:.0f} % of its light in {} sr: relit through each probe's "
                                            "blurred visibility, its shadows' edges are far from a rebake's "
                                            "(docs/RELIGHTING.md)",
                                            which, 100.0 * share, kConcentratedSolidAngle));
  }
  const SkyChange change = relightVolume(volume, *basis, newSky, newSkyDescription, request.volumePath);
  report.visibility = change.visibility;
  report.oldSkyRemoved = change.oldSkyRemoved;
  report.toSky = volume.coarsest().settings.at("sky");
  report.bakedSky = volume.coarsest().settings.at("baked_sky");
  report.changes.push_back("the sky each probe sees directly: the old one taken away " + report.oldSkyRemoved +
                           "; the new one added through the stored visibility: " + report.visibility);
  report.bounceScaled = change.bounceScaled;
  if (change.bounceScaled)
    report.changes.push_back("the sky's light off surfaces (grids sky_bounced_*): scaled per probe and channel by the "
                             "new sky's flux through its map over the old one's, approximately (docs/RELIGHTING.md)");
  else if (report.bounces > 0 && simulated(first, "bounces"))
    report.keeps.push_back("light the sky sends through bounces off surfaces: as baked under " + report.bakedSky);
  if (report.otherLights)
    report.keeps.push_back("light from lamps and emissive surfaces, direct and bounced");
  report.engineExport = writeLevels(volume, *basis, request.output);
  report.seconds = secondsSince(start);
  return report;
}

}  // namespace baker
