#pragma once
#include <string>
#include <vector>

#include "volume/Shard.h"
#include "volume/Volume.h"

namespace baker {

// The whole volume of a bake cut into shards, put together from its parts in any order: every
// probe of a shard's bricks comes from that shard's part, then the Invalid probes are filled
// over the whole grid exactly as a one-process bake fills them, so the result is the same bits.
// Each part is checked against the first before anything of it is used; a mismatch is an
// InputError naming the part and the field (basis, grid, a setting, the shard).
class VolumeAssembly {
 public:
  // `first` (named `firstName` in errors) decides the bake every other part must belong to.
  VolumeAssembly(const Volume& first, const std::string& firstName);

  // Adds a part: the same bake as the first, a shard not given before, nothing baked outside its
  // own bricks.
  void add(const Volume& part, const std::string& name);
  // Adds a part baked in this process (an MPI rank's own), copied as it is: no file, so nothing
  // to check but the shard.
  void addBaked(const Volume& part);
  // Adds the values of shard `shard`'s bricks as packBricks wrote them (a rank's part sent over
  // MPI): no file, so nothing to check but the shard and the size.
  void addPacked(const Shard& shard, const std::vector<float>& packed);
  // Every shard given: the filled whole volume. InputError naming the shards missing otherwise.
  Volume finish();

 private:
  // The values of `shard`'s bricks from `part`, straight into the whole volume (no packed copy).
  void copyBricks(const Volume& part, const Shard& shard);

  Volume whole_;
  std::string firstName_;
  std::vector<std::string> given_;  // per shard: the part that holds it, "" until given
};

// `volume`'s grid, basis, numbers per probe, settings and shard, without values or rows.
Volume volumeWithoutValues(const Volume& volume);
// Sizes `volume`'s arrays for the probes its rows hold: zeros, every probe Invalid.
void holdZeroProbes(Volume& volume);
// Records that part `name` gives `shard` (`given`: per shard, the part that gave it, or "");
// InputError when another part gave it already.
void claimShard(std::vector<std::string>& given, const Shard& shard, const std::string& name);
// InputError listing the shards no part gave.
void requireEveryShard(const std::vector<std::string>& given);

// InputError naming `name` and the first field in which `part` is not a part of the same bake
// as `first` (the shard count, basis, grid, every setting), or not a part at all.
void requireSameBake(const Volume& part, const std::string& name, const Volume& first, const std::string& firstName);

// A part's values for its shard's bricks, probe by probe in brick order: state, offset (3),
// coefficients, sky visibility, distance moments; what a rank sends to the rank that writes the
// volume.
std::vector<float> packBricks(const Volume& part, const std::vector<std::int64_t>& bricks);
// Reads one probe as packBricks packs it into row `row` of `volume` and returns where the next
// starts; nullptr, reading nothing, when its state is not a whole number below `stateLimit`.
const float* unpackProbe(const float* in, Volume& volume, std::int64_t row, int stateLimit);
// How many values packBricks packs per probe of a volume like `like`.
int packedValuesPerProbe(const Volume& like);
// The size of packBricks's result for these bricks of `like`'s grid.
std::size_t packedSize(const Volume& like, const std::vector<std::int64_t>& bricks);
// The same for the probes of `bricks` that `rows` holds (some sub-bricks of an adaptive level).
std::size_t packedSize(const Volume& like, const ProbeRows& rows, const std::vector<std::int64_t>& bricks);

}  // namespace baker
