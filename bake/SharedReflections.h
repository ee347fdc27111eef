#pragma once
#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "bake/PathIntegrator.h"
#include "scene/HugePageAllocator.h"

namespace baker {

// What the paths of a group of probes bring back from the surfaces their rays first hit, shared
// between the probes. Neighbouring probes see the same surfaces, and each traces its own paths
// from them: the light a first hit receives after another reflection or more (what its path
// brings back from the second vertex on, over the albedo at the hit) is averaged over every
// first hit of the group in the same cell (a cube of `cellSize` on one instance, face, the normal's
// main axis and its sign), and each hit reflects that mean by its own albedo. The first hit's
// direct light stays its own: near an emitter it varies within millimetres (the bright ring a
// double-sided panel's back lights on the ceiling beside it), which no cell could average
// without bias. A probe's estimate then draws on its neighbours' paths: its noise falls with the
// number of paths that reach its cells, for a bias of the indirect light's variation across a
// cell. Means are summed in the order of the probes and their rays, so a group's result does not
// depend on which threads traced it.
class SharedReflections {
 public:
  // Memory for one group's samples; a bake shares within groups of consecutive probes that fit.
  static constexpr std::size_t kGroupBytes = std::size_t(128) << 20;
  // Probes per group: as many of `rays` rays as kGroupBytes holds (at least one), whatever the
  // thread count, so that volumes do not depend on it.
  static int groupProbes(int rays, bool skyBounced);

  // `skyBounced`: the sky's light off surfaces (PathIntegrator's skyBounced) is shared as well.
  SharedReflections(float cellSize, int rays, bool skyBounced);

  // Starts a group of `probes` probes.
  void startGroup(int probes);
  // Probe `slot`'s rays, as PathIntegrator::trace described them.
  void record(int slot, const FirstReflection* first, const Eigen::Vector3f* reflected,
              const Eigen::Vector3f* skyBounced);
  // Once every probe of the group is recorded: the cells' means.
  void share();
  // What ray r of probe `slot` reflects of its cell's mean, and of its mean sky light off
  // surfaces (0 where the ray's first hit reflects nothing).
  Eigen::Vector3f reflected(int slot, int r) const;
  Eigen::Vector3f skyBounced(int slot, int r) const;

 private:
  struct Cell {
    std::int32_t x, y, z;   // the cube's index along each axis
    std::uint32_t surface;  // instance, front or back face, normal axis and sign; kNoSurface: no reflection
    bool operator==(const Cell& o) const { return x == o.x && y == o.y && z == o.z && surface == o.surface; }
  };
  struct Sample {
    Cell cell;
    Eigen::Vector3f incoming;  // reflected over albedo, per channel (0 where the albedo is)
    Eigen::Vector3f albedo;
  };
  struct Mean {
    Eigen::Vector3f light, sky;
  };
  struct Sums;
  class CellNumbers;
  static constexpr std::uint32_t kNoSurface = ~std::uint32_t(0);
  Cell cellOf(const FirstReflection& first) const;
  std::size_t index(int slot, int r) const { return std::size_t(slot) * std::size_t(rays_) + std::size_t(r); }

  float cellSize_;
  int rays_;
  bool shareSky_;
  std::vector<Sample, HugePageAllocator<Sample>> samples_;
  std::vector<Eigen::Vector3f, HugePageAllocator<Eigen::Vector3f>> skyIncoming_;  // with shareSky_
  std::vector<Mean> means_;
  std::vector<std::uint32_t, HugePageAllocator<std::uint32_t>> meanOf_;  // of each sample, after share()
};

}  // namespace baker
