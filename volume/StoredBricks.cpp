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

// Calls f(i, j, k) for each held probe that is not Invalid.
template <typename F>
void forProbesOutsideGeometry(const Volume& v, F f) {
  const ProbeGrid& g = v.grid;
  for (std::int64_t brick : heldBricks(v)) {
    const Eigen::Vector3i lo = g.brickCorner(brick), hi = lo + g.brickExtent(brick);
    for (int k = lo.z(); k < hi.z(); ++k)
      for (int j = lo.y(); j < hi.y(); ++j)
        for (int i = lo.x(); i < hi.x(); ++i)
          if (v.states[std::size_t(v.rows.row(g, i, j, k))] != ProbeState::Invalid) f(i, j, k);
  }
}

}  // namespace

std::vector<bool> bricksWorthStoring(const Volume& v) {
  const ProbeGrid& g = v.grid;
  if (v.states.empty()) return std::vector<bool>(std::size_t(g.brickCount()), true);
  std::vector<bool> keep(std::size_t(g.brickCount()), false);
  forProbesOutsideGeometry(v, [&](int i, int j, int k) {
    // The bricks of the probes i−1…i+1 (and so on), inside the grid: at most two per axis.
    const Eigen::Vector3i p(i, j, k);
    Eigen::Vector3i lo, hi;
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::max(p[a] - 1, 0) / kBrickSize;
      hi[a] = std::min(p[a] + 1, g.dims[a] - 1) / kBrickSize;
    }
    for (int bk = lo.z(); bk <= hi.z(); ++bk)
      for (int bj = lo.y(); bj <= hi.y(); ++bj)
        for (int bi = lo.x(); bi <= hi.x(); ++bi) {
          const std::int64_t brick = g.brickOf(bi * kBrickSize, bj * kBrickSize, bk * kBrickSize);
          if (v.rows.holdsBrick(brick)) keep[std::size_t(brick)] = true;
        }
  });
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
  move(v.coefficients, v.coefficientsPerProbe);
  move(v.visibility, v.visibilityPerProbe);
  if (!v.states.empty()) move(v.states, 1);
  if (!v.offsets.empty()) move(v.offsets, 1);
}

void resizeRows(Volume& v, std::int64_t rows) {
  v.coefficients.resize(std::size_t(rows * v.coefficientsPerProbe));
  v.visibility.resize(std::size_t(rows * v.visibilityPerProbe));
  if (!v.states.empty()) v.states.resize(std::size_t(rows));
  if (!v.offsets.empty()) v.offsets.resize(std::size_t(rows));
}

// A volume holding every probe, its rows in grid order: copied brick by brick into new arrays.
Volume keepBricksOfWholeVolume(Volume volume, const std::vector<std::int64_t>& kept) {
  const std::vector<float> coefficients = std::move(volume.coefficients), visibility = std::move(volume.visibility);
  const std::vector<ProbeState> states = std::move(volume.states);
  const std::vector<Eigen::Vector3f> offsets = std::move(volume.offsets);
  const ProbeGrid& g = volume.grid;
  const int c = volume.coefficientsPerProbe, s = volume.visibilityPerProbe;
  volume.rows = ProbeRows(g, kept);
  const std::size_t rows = std::size_t(volume.rows.count(g));
  volume.coefficients.assign(rows * std::size_t(c), 0.0f);
  volume.visibility.assign(rows * std::size_t(s), 0.0f);
  volume.states.assign(states.empty() ? 0 : rows, ProbeState::Invalid);
  volume.offsets.assign(offsets.empty() ? 0 : rows, Eigen::Vector3f::Zero());
  for (std::int64_t brick : kept) {
    const Eigen::Vector3i lo = g.brickCorner(brick), hi = lo + g.brickExtent(brick);
    for (int k = lo.z(); k < hi.z(); ++k)
      for (int j = lo.y(); j < hi.y(); ++j)
        for (int i = lo.x(); i < hi.x(); ++i) {
          const std::int64_t from = g.linearIndex(i, j, k), to = volume.rows.row(g, i, j, k);
          std::copy_n(coefficients.begin() + from * c, c, volume.coefficients.begin() + to * c);
          std::copy_n(visibility.begin() + from * s, s, volume.visibility.begin() + to * s);
          if (!states.empty()) volume.states[std::size_t(to)] = states[std::size_t(from)];
          if (!offsets.empty()) volume.offsets[std::size_t(to)] = offsets[std::size_t(from)];
        }
  }
  return volume;
}

}  // namespace

std::vector<std::int64_t> heldBricksInOrder(const Volume& volume) {
  std::vector<std::int64_t> bricks = heldBricks(volume);
  std::sort(bricks.begin(), bricks.end());
  return bricks;
}

Volume keepBricks(Volume volume, const std::vector<bool>& keep) {
  const std::vector<std::int64_t> held = heldBricks(volume);
  std::vector<std::int64_t> kept;
  for (std::int64_t brick : held)
    if (keep[std::size_t(brick)]) kept.push_back(brick);
  if (kept.size() == held.size()) return volume;
  if (volume.rows.holdsEveryProbe()) return keepBricksOfWholeVolume(std::move(volume), kept);
  // Bricks keep their order and sizes, so each kept brick's rows move towards the front, never
  // past a brick still to move: the arrays are compacted in place, not held twice.
  const ProbeGrid& g = volume.grid;
  const ProbeRows rows(g, kept);
  for (std::int64_t brick : kept) {
    const Eigen::Vector3i corner = g.brickCorner(brick);
    moveRows(volume, volume.rows.row(g, corner.x(), corner.y(), corner.z()), rows.row(g, corner.x(), corner.y(), corner.z()),
             g.brickExtent(brick).cast<std::int64_t>().prod());
  }
  volume.rows = rows;
  resizeRows(volume, rows.count(g));
  return volume;
}

}  // namespace baker
