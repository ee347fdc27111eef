#include "volume/StoredBricks.h"

#include <algorithm>

namespace baker {
namespace {

// The held bricks, in row order.
std::vector<std::int64_t> heldBricks(const Volume& v) {
  if (!v.rows.holdsEveryProbe()) return v.rows.bricks();
  std::vector<std::int64_t> all(std::size_t(v.grid.brickCount()));
  for (std::size_t b = 0; b < all.size(); ++b) all[b] = std::int64_t(b);
  return all;
}

// Calls f(i, j, k) for each held probe traced outside geometry (Valid or Relocated). A border
// probe (Interpolated) is not traced, and holds what the coarser levels give there anyway.
template <typename F>
void forProbesOutsideGeometry(const Volume& v, F f) {
  const ProbeGrid& g = v.grid;
  for (std::int64_t brick : heldBricks(v))
    forEachHeldProbeOfBrick(g, v.rows, brick, [&](int i, int j, int k, std::int64_t row) {
      const ProbeState state = v.states[std::size_t(row)];
      if (state == ProbeState::Valid || state == ProbeState::Relocated) f(i, j, k);
    });
}

// Per linear brick index, the held sub-bricks holding a probe traced outside geometry or next to
// one.
std::vector<std::uint8_t> subBricksNearTracedProbes(const Volume& v) {
  const ProbeGrid& g = v.grid;
  std::vector<std::uint8_t> keep(std::size_t(g.brickCount()), 0);
  if (v.states.empty()) {
    for (std::size_t b = 0; b < keep.size(); ++b) keep[b] = v.rows.subBricks(g, std::int64_t(b));
    return keep;
  }
  forProbesOutsideGeometry(v, [&](int i, int j, int k) {
    // The sub-bricks of the probes i−1…i+1 (and so on), inside the grid: at most two per axis.
    const Eigen::Vector3i p(i, j, k);
    Eigen::Vector3i lo, hi;
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::max(p[a] - 1, 0) / kSubBrickSize;
      hi[a] = std::min(p[a] + 1, g.dims[a] - 1) / kSubBrickSize;
    }
    for (int sk = lo.z(); sk <= hi.z(); ++sk)
      for (int sj = lo.y(); sj <= hi.y(); ++sj)
        for (int si = lo.x(); si <= hi.x(); ++si) {
          const Eigen::Vector3i q = kSubBrickSize * Eigen::Vector3i(si, sj, sk);
          const std::int64_t brick = g.brickOf(q.x(), q.y(), q.z());
          keep[std::size_t(brick)] |= std::uint8_t(v.rows.subBricks(g, brick) & subBrickBit(q.x(), q.y(), q.z()));
        }
  });
  return keep;
}

}  // namespace

std::vector<bool> bricksWorthStoring(const Volume& v) {
  // A brick is worth storing when one of its held probes is next to a traced one.
  const std::vector<std::uint8_t> masks = subBricksNearTracedProbes(v);
  std::vector<bool> keep(masks.size());
  for (std::size_t b = 0; b < masks.size(); ++b) keep[b] = masks[b] != 0;
  return keep;
}

std::vector<bool> bricksWithAProbeOutsideGeometry(const Volume& v) {
  const ProbeGrid& g = v.grid;
  if (v.states.empty()) return std::vector<bool>(std::size_t(g.brickCount()), true);
  std::vector<bool> keep(std::size_t(g.brickCount()), false);
  forProbesOutsideGeometry(v, [&](int i, int j, int k) { keep[std::size_t(g.brickOf(i, j, k))] = true; });
  return keep;
}

namespace {

// Moves row ranges forward within each per-probe array: `from` and `to` the first rows, `count`.
void moveRows(Volume& v, std::int64_t from, std::int64_t to, std::int64_t count) {
  const auto move = [&](auto& values, std::int64_t width) {
    std::copy(values.begin() + from * width, values.begin() + (from + count) * width, values.begin() + to * width);
  };
  for (const auto& [values, width] : v.floatRows()) move(*values, width);
  if (!v.states.empty()) move(v.states, 1);
  if (!v.offsets.empty()) move(v.offsets, 1);
}

void resizeRows(Volume& v, std::int64_t rows) {
  for (const auto& [values, width] : v.floatRows()) values->resize(std::size_t(rows * width));
  if (!v.states.empty()) v.states.resize(std::size_t(rows));
  if (!v.offsets.empty()) v.offsets.resize(std::size_t(rows));
}

// A volume holding every probe, its rows in grid order: copied brick by brick into new arrays.
Volume keepBricksOfWholeVolume(Volume volume, const std::vector<std::int64_t>& kept, const std::vector<std::uint8_t>& masks) {
  std::vector<std::vector<float>> whole;
  for (const auto& [values, width] : volume.floatRows()) whole.push_back(std::move(*values));
  const std::vector<ProbeState> states = std::move(volume.states);
  const std::vector<Eigen::Vector3f> offsets = std::move(volume.offsets);
  const ProbeGrid& g = volume.grid;
  volume.rows = ProbeRows(g, kept, masks);
  const std::size_t rows = std::size_t(volume.rows.count(g));
  const auto arrays = volume.floatRows();
  for (const auto& [values, width] : arrays) values->assign(rows * std::size_t(width), 0.0f);
  volume.states.assign(states.empty() ? 0 : rows, ProbeState::Invalid);
  volume.offsets.assign(offsets.empty() ? 0 : rows, Eigen::Vector3f::Zero());
  for (std::int64_t brick : kept)
    forEachHeldProbeOfBrick(g, volume.rows, brick, [&](int i, int j, int k, std::int64_t to) {
      const std::int64_t from = g.linearIndex(i, j, k);
      for (std::size_t a = 0; a < arrays.size(); ++a) {
        const int w = arrays[a].width;
        std::copy_n(whole[a].begin() + from * w, w, arrays[a].values->begin() + to * w);
      }
      if (!states.empty()) volume.states[std::size_t(to)] = states[std::size_t(from)];
      if (!offsets.empty()) volume.offsets[std::size_t(to)] = offsets[std::size_t(from)];
    });
  return volume;
}

}  // namespace

std::vector<std::int64_t> heldBricksInOrder(const Volume& volume) {
  std::vector<std::int64_t> bricks = heldBricks(volume);
  std::sort(bricks.begin(), bricks.end());
  return bricks;
}

Volume keepBricks(Volume volume, const std::vector<bool>& keep) {
  const ProbeGrid& g = volume.grid;
  const std::vector<std::int64_t> held = heldBricks(volume);
  std::vector<std::int64_t> kept;
  std::vector<std::uint8_t> masks;  // a kept brick keeps the sub-bricks it holds
  for (std::int64_t brick : held)
    if (keep[std::size_t(brick)]) {
      kept.push_back(brick);
      masks.push_back(volume.rows.subBricks(g, brick));
    }
  if (kept.size() == held.size()) return volume;
  if (volume.rows.holdsEveryProbe()) return keepBricksOfWholeVolume(std::move(volume), kept, masks);
  // Bricks keep their order and sizes, so each kept brick's rows move towards the front, never
  // past a brick still to move: the arrays are compacted in place, not held twice.
  const ProbeRows rows(g, kept, masks);
  for (std::int64_t brick : kept)
    moveRows(volume, volume.rows.firstRowOfBrick(brick), rows.firstRowOfBrick(brick), rows.probesHeld(g, brick));
  volume.rows = rows;
  resizeRows(volume, rows.count(g));
  return volume;
}

}  // namespace baker
