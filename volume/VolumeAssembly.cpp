#include "volume/VolumeAssembly.h"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

#include "common/Error.h"
#include "volume/InvalidProbeFill.h"

namespace baker {
namespace {

InputError notAPart(const std::string& name) {
  return InputError(fmt::format("{}: not a shard's part (no baker.shard); a part is baked as one shard of a bake", name));
}

std::string vectorText(const Eigen::Vector3d& v) { return fmt::format("({:.17g}, {:.17g}, {:.17g})", v.x(), v.y(), v.z()); }

}  // namespace

void requireSameBake(const Volume& part, const std::string& name, const Volume& first, const std::string& firstName) {
  const auto mismatch = [&](const std::string& field, const std::string& here, const std::string& there) {
    throw InputError(fmt::format("{}: {} is {}, but {} has {}: the parts are not of one bake", name, field, here,
                                 firstName, there));
  };
  if (!part.shard) throw notAPart(name);
  if (part.shard->count != first.shard->count)
    mismatch("baker.shard", shardName(*part.shard), fmt::format("a part of {} shards", first.shard->count));
  if (part.basisName != first.basisName) mismatch("baker.basis", part.basisName, first.basisName);
  const ProbeGrid &g = part.grid, &f = first.grid;
  if (g.dims != f.dims)
    mismatch("baker.dims", fmt::format("({}, {}, {})", g.dims.x(), g.dims.y(), g.dims.z()),
             fmt::format("({}, {}, {})", f.dims.x(), f.dims.y(), f.dims.z()));
  if (g.origin != f.origin) mismatch("baker.origin", vectorText(g.origin), vectorText(f.origin));
  if (g.spacing != f.spacing) mismatch("baker.spacing", fmt::format("{:.17g}", g.spacing), fmt::format("{:.17g}", f.spacing));
  if (part.coefficientsPerProbe != first.coefficientsPerProbe)
    mismatch("baker.coefficients_per_probe", std::to_string(part.coefficientsPerProbe),
             std::to_string(first.coefficientsPerProbe));
  if (part.visibilityPerProbe != first.visibilityPerProbe)
    mismatch("baker.visibility_per_probe", std::to_string(part.visibilityPerProbe),
             std::to_string(first.visibilityPerProbe));
  if (part.keepsSkyDirect != first.keepsSkyDirect)
    mismatch("baker.sky_direct", part.keepsSkyDirect ? "present" : "absent", first.keepsSkyDirect ? "present" : "absent");
  if (part.keepsSkyBounced != first.keepsSkyBounced)
    mismatch("baker.sky_bounced", part.keepsSkyBounced ? "present" : "absent",
             first.keepsSkyBounced ? "present" : "absent");
  const DistanceMapLayout &d = part.distanceMap, &e = first.distanceMap;
  if (d.size != e.size || d.cap != e.cap || d.skyVisibility != e.skyVisibility)
    mismatch("baker.distance_map", fmt::format("size {} cap {:.17g} sky {}", d.size, d.cap, d.skyVisibility),
             fmt::format("size {} cap {:.17g} sky {}", e.size, e.cap, e.skyVisibility));
  const auto setting = [](const Volume& v, const std::string& key) {
    const auto it = v.settings.find(key);
    return it == v.settings.end() ? std::string("none") : "\"" + it->second + "\"";
  };
  if (setting(part, "scene_fnv1a64") != setting(first, "scene_fnv1a64"))
    throw InputError(fmt::format("{}: baked from another scene (baker.setting.scene_fnv1a64 is {}, {} has {})", name,
                                 setting(part, "scene_fnv1a64"), firstName, setting(first, "scene_fnv1a64")));
  for (const Volume* v : {&part, &first})
    for (const auto& [key, value] : v->settings)
      if (setting(part, key) != setting(first, key))
        mismatch("baker.setting." + key, setting(part, key), setting(first, key));
}


Volume volumeWithoutValues(const Volume& volume) {
  Volume header;
  header.grid = volume.grid;
  header.basisName = volume.basisName;
  header.coefficientsPerProbe = volume.coefficientsPerProbe;
  header.keepsSkyDirect = volume.keepsSkyDirect;
  header.keepsSkyBounced = volume.keepsSkyBounced;
  header.visibilityPerProbe = volume.visibilityPerProbe;
  header.distanceMap = volume.distanceMap;
  header.sky = volume.sky;
  header.settings = volume.settings;
  header.shard = volume.shard;
  return header;
}

void holdZeroProbes(Volume& volume) {
  const std::size_t probes = std::size_t(volume.rows.count(volume.grid));
  for (const auto& [values, width] : volume.floatRows()) values->assign(probes * std::size_t(width), 0.0f);
  volume.states.assign(probes, ProbeState::Invalid);
  volume.offsets.assign(probes, Eigen::Vector3f::Zero());
}

void claimShard(std::vector<std::string>& given, const Shard& shard, const std::string& name) {
  std::string& holder = given[std::size_t(shard.index)];
  if (!holder.empty())
    throw InputError(fmt::format("{}: shard {} is given twice (also by {}); give each part once", name,
                                 shardName(shard), holder));
  holder = name;
}

void requireEveryShard(const std::vector<std::string>& given) {
  std::vector<std::string> missing;
  for (std::size_t s = 0; s < given.size(); ++s)
    if (given[s].empty()) missing.push_back(fmt::format("{}/{}", s, given.size()));
  if (!missing.empty())
    throw InputError(fmt::format("shard{} {} missing: every part of the bake must be given once",
                                 missing.size() > 1 ? "s" : "", fmt::join(missing, ", ")));
}

VolumeAssembly::VolumeAssembly(const Volume& first, const std::string& firstName) : firstName_(firstName) {
  if (!first.shard)
    throw notAPart(firstName);
  whole_ = volumeWithoutValues(first);
  holdZeroProbes(whole_);
  given_.assign(std::size_t(first.shard->count), "");
}

void VolumeAssembly::add(const Volume& part, const std::string& name) {
  requireSameBake(part, name, whole_, firstName_);
  // Each probe it holds has a state; a part whose shard has no brick holds none.
  if (part.states.size() * std::size_t(part.coefficientsPerProbe) != part.coefficients.size())
    throw InputError(fmt::format("{}: has no probe_state grid; a shard's part has one", name));
  const Shard shard = *part.shard;
  // A probe outside the part's own bricks would be a brick given twice, or a part of another
  // partition: its reader refused those, reading the part as its own bricks only.
  if (part.rows.holdsEveryProbe())
    throw std::logic_error("VolumeAssembly::add: read parts with PartReading::OwnBricks");
  claimShard(given_, shard, name);
  copyBricks(part, shard);
}

void VolumeAssembly::addBaked(const Volume& part) {
  if (!part.shard || part.shard->count != whole_.shard->count || part.grid.dims != whole_.grid.dims)
    throw std::logic_error("VolumeAssembly::addBaked: not a part of this bake");
  claimShard(given_, *part.shard, "shard " + shardName(*part.shard));
  copyBricks(part, *part.shard);
}

void VolumeAssembly::copyBricks(const Volume& part, const Shard& shard) {
  const auto from = part.floatRows();
  const auto to = whole_.floatRows();
  for (const std::int64_t b : shardBricks(whole_.grid, shard))
    for (const std::int64_t p : probesOfBrick(whole_.grid, b)) {
      const std::int64_t r = part.rowOf(p);
      if (r < 0) throw std::logic_error("VolumeAssembly: a part without one of its own bricks");
      whole_.states[p] = part.states[r];
      whole_.offsets[p] = part.offsets[r];
      for (std::size_t a = 0; a < to.size(); ++a) {
        const int w = to[a].width;
        std::copy_n(from[a].values->begin() + r * w, w, to[a].values->begin() + p * w);
      }
    }
}

void VolumeAssembly::addPacked(const Shard& shard, const std::vector<float>& packed) {
  if (shard.count != whole_.shard->count)
    throw InputError(fmt::format("shard {}: the bake has {} shards", shardName(shard), whole_.shard->count));
  claimShard(given_, shard, "shard " + shardName(shard));
  const std::vector<std::int64_t> bricks = shardBricks(whole_.grid, shard);
  if (packed.size() != packedSize(whole_, bricks))
    throw InputError(fmt::format("shard {}: {} values received, {} expected", shardName(shard), packed.size(),
                                 packedSize(whole_, bricks)));
  const float* in = packed.data();
  for (const std::int64_t b : bricks)
    for (const std::int64_t p : probesOfBrick(whole_.grid, b)) {
      const float* next = unpackProbe(in, whole_, p, int(ProbeState::Relocated) + 1);
      if (!next)
        throw InputError(fmt::format("shard {}: probe {} has state {}, not 0, 1 or 2", shardName(shard), p, *in));
      in = next;
    }
}

const float* unpackProbe(const float* in, Volume& volume, std::int64_t row, int stateLimit) {
  const float state = in[0];
  if (!(state >= 0.0f && state < float(stateLimit) && state == float(int(state)))) return nullptr;
  const std::size_t r = std::size_t(row);
  volume.states[r] = ProbeState(std::uint8_t(state));
  for (int c = 0; c < 3; ++c) volume.offsets[r][c] = in[1 + c];
  in += 4;
  for (const auto& [values, width] : volume.floatRows()) {
    std::copy_n(in, width, values->begin() + row * width);
    in += width;
  }
  return in;
}

Volume VolumeAssembly::finish() {
  requireEveryShard(given_);
  fillInvalidProbes(whole_.grid, whole_.states, whole_.coefficientsPerProbe, whole_.coefficients);
  fillInvalidProbes(whole_.grid, whole_.states, whole_.visibilityPerProbe, whole_.visibility);
  fillInvalidProbes(whole_.grid, whole_.states, whole_.skyDirectPerProbe(), whole_.skyDirect);
  fillInvalidProbes(whole_.grid, whole_.states, whole_.skyBouncedPerProbe(), whole_.skyBounced);
  whole_.shard.reset();
  return std::move(whole_);
}

int packedValuesPerProbe(const Volume& like) {
  int values = 4;  // state and offset
  for (const auto& rows : like.floatRows()) values += rows.width;
  return values;
}

std::size_t packedSize(const Volume& like, const std::vector<std::int64_t>& bricks) {
  return packedSize(like, ProbeRows(), bricks);
}

std::size_t packedSize(const Volume& like, const ProbeRows& rows, const std::vector<std::int64_t>& bricks) {
  std::size_t probes = 0;
  for (const std::int64_t b : bricks) probes += std::size_t(rows.probesHeld(like.grid, b));
  return probes * std::size_t(packedValuesPerProbe(like));
}

std::vector<float> packBricks(const Volume& part, const std::vector<std::int64_t>& bricks) {
  std::vector<float> packed;
  packed.reserve(packedSize(part, part.rows, bricks));
  for (const std::int64_t b : bricks) {
    if (!part.rows.holdsBrick(b)) throw std::logic_error("packBricks: a brick the part does not hold");
    forEachHeldProbeOfBrick(part.grid, part.rows, b, [&](int, int, int, std::int64_t r) {
      packed.push_back(float(part.states[r]));
      packed.insert(packed.end(), part.offsets[r].data(), part.offsets[r].data() + 3);
      for (const auto& [values, width] : part.floatRows())
        packed.insert(packed.end(), values->begin() + r * width, values->begin() + (r + 1) * width);
    });
  }
  return packed;
}

}  // namespace baker
