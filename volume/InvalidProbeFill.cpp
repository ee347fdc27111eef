#include "volume/InvalidProbeFill.h"

#include <algorithm>
#include <stdexcept>

namespace baker {

void fillInvalidProbes(const ProbeGrid& grid, const std::vector<ProbeState>& states, int valuesPerProbe,
                       std::vector<float>& values) {
  fillInvalidProbes(grid, ProbeRows(), states, valuesPerProbe, values);
}

namespace {

enum Mark : std::uint8_t { kUnknown, kQueued, kKnown, kLater };

// Fills, pass after pass, every unknown probe that known ones reach through face neighbours with
// the mean of its known neighbours.
template <typename Neighbours>
void spreadFromKnown(std::int64_t probes, int valuesPerProbe, const Neighbours& forEachFaceNeighbour,
                     std::vector<Mark>& marks, std::vector<float>& values) {
  const std::size_t width = std::size_t(valuesPerProbe);
  std::vector<std::int64_t> frontier;
  for (std::int64_t p = 0; p < probes; ++p) {
    if (marks[p] != kUnknown) continue;
    bool besideKnown = false;
    forEachFaceNeighbour(p, [&](std::int64_t n) { besideKnown |= marks[n] == kKnown; });
    if (besideKnown) {
      marks[p] = kQueued;
      frontier.push_back(p);
    }
  }
  std::vector<float> means;
  std::vector<double> sum(width);
  std::vector<std::int64_t> next;
  while (!frontier.empty()) {
    means.assign(frontier.size() * width, 0.0f);
    for (std::size_t f = 0; f < frontier.size(); ++f) {
      std::fill(sum.begin(), sum.end(), 0.0);
      int sources = 0;
      forEachFaceNeighbour(frontier[f], [&](std::int64_t n) {
        if (marks[n] != kKnown) return;
        ++sources;
        for (std::size_t c = 0; c < width; ++c) sum[c] += values[n * valuesPerProbe + c];
      });
      // Every queued probe has a known neighbour: that is how it was queued.
      for (std::size_t c = 0; c < width; ++c) means[f * width + c] = float(sum[c] / sources);
    }
    next.clear();
    for (std::size_t f = 0; f < frontier.size(); ++f) {
      const std::int64_t p = frontier[f];
      std::copy_n(means.begin() + f * width, width, values.begin() + p * valuesPerProbe);
      marks[p] = kKnown;
    }
    for (const std::int64_t p : frontier)
      forEachFaceNeighbour(p, [&](std::int64_t n) {
        if (marks[n] != kUnknown) return;
        marks[n] = kQueued;
        next.push_back(n);
      });
    frontier.swap(next);
  }
}

}  // namespace

void fillInvalidProbes(const ProbeGrid& grid, const ProbeRows& rows, const std::vector<ProbeState>& states,
                       int valuesPerProbe, std::vector<float>& values) {
  const std::int64_t probes = rows.count(grid);
  if (valuesPerProbe < 0 || std::int64_t(states.size()) != probes ||
      std::int64_t(values.size()) != probes * valuesPerProbe)
    throw std::invalid_argument("fillInvalidProbes: states and values do not match the grid");
  const std::size_t width = std::size_t(valuesPerProbe);
  const std::int64_t dx = grid.dims.x(), dy = grid.dims.y(), dz = grid.dims.z();
  // Face neighbours are the nearest valid data, and every probe of the grid is reached through
  // them; the 26 would add corners √3 spacings away without reaching anything new.
  const auto forEachFaceNeighbour = [&](std::int64_t row, auto&& visit) {
    const std::int64_t p = rows.probeAt(grid, row);
    const int i = int(p % dx), j = int((p / dx) % dy), k = int(p / (dx * dy));
    const auto visitHeld = [&](int a, int b, int c) {
      if (const std::int64_t n = rows.row(grid, a, b, c); n >= 0) visit(n);
    };
    if (i > 0) visitHeld(i - 1, j, k);
    if (i + 1 < dx) visitHeld(i + 1, j, k);
    if (j > 0) visitHeld(i, j - 1, k);
    if (j + 1 < dy) visitHeld(i, j + 1, k);
    if (k > 0) visitHeld(i, j, k - 1);
    if (k + 1 < dz) visitHeld(i, j, k + 1);
  };

  // Known probes can feed their neighbours; a queued one is filled by the current pass and
  // becomes known only after it, so a pass reads nothing it wrote itself. Probes holding another
  // level's values (Interpolated, an adaptive level's border) feed only probes that no traced
  // probe reaches: inside geometry the fill should carry the light of the surface the probe is
  // under, as in a uniform bake, not the coarser level's.
  std::vector<Mark> marks(std::size_t(probes), kKnown);
  for (std::int64_t p = 0; p < probes; ++p)
    if (states[p] == ProbeState::Invalid) {
      marks[p] = kUnknown;
      std::fill_n(values.begin() + p * valuesPerProbe, width, 0.0f);
    } else if (states[p] == ProbeState::Interpolated) {
      marks[p] = kLater;
    }
  const auto spread = [&] { spreadFromKnown(probes, valuesPerProbe, forEachFaceNeighbour, marks, values); };
  spread();
  std::replace(marks.begin(), marks.end(), kLater, kKnown);
  spread();
}

}  // namespace baker
