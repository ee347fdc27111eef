#include "bake/SharedReflections.h"

#include <algorithm>
#include <cmath>

#include "bake/PathRandom.h"

namespace baker {

struct SharedReflections::Sums {
  double light[3] = {0.0, 0.0, 0.0}, sky[3] = {0.0, 0.0, 0.0};
  std::int64_t count[3] = {0, 0, 0};
};

// Cells numbered by open addressing (linear probing): a group's samples are millions, and a
// general-purpose map's node per cell cost more than the sharing saves.
class SharedReflections::CellNumbers {
 public:
  // The number of `cell`, given `next` if it is new.
  std::uint32_t numberOf(const Cell& cell, std::uint32_t next) {
    if (2 * (used_ + 1) > slots_.size()) grow();
    for (std::size_t i = slotOf(cell);; i = (i + 1) & (slots_.size() - 1)) {
      Slot& slot = slots_[i];
      if (slot.number == kEmpty) {
        slot = {cell, next};
        ++used_;
        return next;
      }
      if (slot.cell == cell) return slot.number;
    }
  }

 private:
  struct Slot {
    Cell cell;
    std::uint32_t number;
  };
  static constexpr std::uint32_t kEmpty = ~std::uint32_t(0);
  std::size_t slotOf(const Cell& cell) const {
    const std::uint64_t xy = (std::uint64_t(std::uint32_t(cell.x)) << 32) | std::uint32_t(cell.y);
    const std::uint64_t z = (std::uint64_t(std::uint32_t(cell.z)) << 32) | cell.surface;
    return std::size_t(PathRandom::scramble(PathRandom::scramble(xy) ^ z)) & (slots_.size() - 1);
  }
  void grow() {
    std::vector<Slot> old(std::max<std::size_t>(1024, 2 * slots_.size()), Slot{{0, 0, 0, 0}, kEmpty});
    old.swap(slots_);
    used_ = 0;
    for (const Slot& slot : old)
      if (slot.number != kEmpty) numberOf(slot.cell, slot.number);
  }
  std::vector<Slot> slots_;
  std::size_t used_ = 0;
};

int SharedReflections::groupProbes(int rays, bool skyBounced) {
  const std::size_t perRay = sizeof(Sample) + sizeof(std::uint32_t) + (skyBounced ? sizeof(Eigen::Vector3f) : 0);
  return int(std::max<std::size_t>(1, kGroupBytes / (perRay * std::size_t(std::max(rays, 1)))));
}

SharedReflections::SharedReflections(float cellSize, int rays, bool skyBounced)
    : cellSize_(cellSize), rays_(rays), shareSky_(skyBounced) {}

void SharedReflections::startGroup(int probes) {
  samples_.resize(std::size_t(probes) * std::size_t(rays_));
  if (shareSky_) skyIncoming_.resize(samples_.size());
  means_.clear();
}

SharedReflections::Cell SharedReflections::cellOf(const FirstReflection& first) const {
  // Indices beyond int32 (a point 2^31 cells from the origin) are clamped: no scene is that large
  // at the smallest cell the request admits.
  const auto index = [&](int a) {
    const double i = std::floor(double(first.point[a]) / double(cellSize_));
    return std::int32_t(std::clamp(i, -2147483648.0, 2147483647.0));
  };
  int axis = 0;
  first.normal.cwiseAbs().maxCoeff(&axis);
  const auto side = std::uint32_t(2 * axis + (first.normal[axis] < 0.0f ? 1 : 0));
  // 28 bits of instance: beyond 2^28 instances, two share a number.
  return {index(0), index(1), index(2), (first.instance << 4) | (first.frontFace ? 8u : 0u) | side};
}

void SharedReflections::record(int slot, const FirstReflection* first, const Eigen::Vector3f* reflected,
                               const Eigen::Vector3f* skyBounced) {
  for (int r = 0; r < rays_; ++r) {
    Sample& out = samples_[index(slot, r)];
    if (!first[r].reflects) {
      out.cell = {0, 0, 0, kNoSurface};
      continue;
    }
    out.cell = cellOf(first[r]);
    out.albedo = first[r].albedo;
    for (int c = 0; c < 3; ++c) {
      const bool reflects = first[r].albedo[c] > 0.0f;
      out.incoming[c] = reflects ? reflected[r][c] / first[r].albedo[c] : 0.0f;
      if (shareSky_) skyIncoming_[index(slot, r)][c] = reflects ? skyBounced[r][c] / first[r].albedo[c] : 0.0f;
    }
  }
}

void SharedReflections::share() {
  // One pass in the order of the probes and their rays: each cell's sums come out the same
  // whichever threads traced the samples. A cell is numbered where it first appears.
  std::vector<Sums> sums;
  CellNumbers numbers;
  meanOf_.resize(samples_.size());
  for (std::size_t k = 0; k < samples_.size(); ++k) {
    const Sample& s = samples_[k];
    if (s.cell.surface == kNoSurface) continue;
    const std::uint32_t m = numbers.numberOf(s.cell, std::uint32_t(sums.size()));
    if (m == sums.size()) sums.emplace_back();
    Sums& cell = sums[m];
    // A channel the albedo zeroes brought nothing back in it: it says nothing of the light.
    for (int c = 0; c < 3; ++c)
      if (s.albedo[c] > 0.0f) {
        cell.light[c] += s.incoming[c];
        if (shareSky_) cell.sky[c] += skyIncoming_[k][c];
        ++cell.count[c];
      }
    meanOf_[k] = m;
  }
  means_.assign(sums.size(), Mean{Eigen::Vector3f::Zero(), Eigen::Vector3f::Zero()});
  for (std::size_t m = 0; m < sums.size(); ++m)
    for (int c = 0; c < 3; ++c)
      if (sums[m].count[c] > 0) {
        means_[m].light[c] = float(sums[m].light[c] / double(sums[m].count[c]));
        means_[m].sky[c] = float(sums[m].sky[c] / double(sums[m].count[c]));
      }
}

Eigen::Vector3f SharedReflections::reflected(int slot, int r) const {
  const Sample& s = samples_[index(slot, r)];
  if (s.cell.surface == kNoSurface) return Eigen::Vector3f::Zero();
  return s.albedo.cwiseProduct(means_[meanOf_[index(slot, r)]].light);
}

Eigen::Vector3f SharedReflections::skyBounced(int slot, int r) const {
  const Sample& s = samples_[index(slot, r)];
  if (s.cell.surface == kNoSurface) return Eigen::Vector3f::Zero();
  return s.albedo.cwiseProduct(means_[meanOf_[index(slot, r)]].sky);
}

}  // namespace baker
