#include "bake/ProbeValidity.h"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <tuple>

#include "basis/DirectionSet.h"

namespace baker {
namespace {

// Re-tests per probe: the nearest back faces are the likely ways out, and a probe deep inside
// a solid must not cost a full test for each of its back-face rays.
constexpr int kMaxCandidates = 8;
// How far past the back face a moved probe lands, in spacings: clear of the surface without
// spending much of the offset budget.
constexpr float kMarginFraction = 0.02f;
// The margin never shrinks below this many float steps of the coordinates involved, so a probe
// far from the origin, or in a tiny scene, does not round back onto the surface it crossed.
constexpr float kMarginSteps = 16.0f;
// The check for other surfaces within the margin starts this far into it, in margins: the
// surface being crossed may report its distance a rounding error later than the first trace did.
constexpr float kCrossedSurfaceSkip = 0.25f;

struct BackfaceHit {
  float distance;
  int direction;
};

// How far behind the probe its test rays start, in float steps of its coordinates (or of the
// spacing, near the origin). A ray starting exactly on a surface does not hit it, so a probe a
// grid put on a floor or an edge would see the sky through it. Started a little behind, every
// ray that leaves into a surface meets its back face at distance ~0: the probe reads as inside,
// and is moved off through that face like any other.
float startBehind(const Eigen::Vector3f& position, float spacing) {
  return kMarginSteps * std::numeric_limits<float>::epsilon() * std::max(position.cwiseAbs().maxCoeff(), spacing);
}

std::vector<BackfaceHit> traceBackfaces(const RayTracer& tracer, const Eigen::Vector3f& origin, float behind,
                                        const std::vector<Eigen::Vector3f>& directions, std::int64_t* raysTraced) {
  constexpr int kPacket = 8;
  std::vector<BackfaceHit> backfaces;
  Ray rays[kPacket];
  Hit hits[kPacket];
  const int count = int(directions.size());
  for (int first = 0; first < count; first += kPacket) {
    const int packet = std::min(kPacket, count - first);
    for (int i = 0; i < packet; ++i) {
      const Eigen::Vector3f& d = directions[first + i];
      rays[i] = {origin - behind * d, d, 0.0f, std::numeric_limits<float>::infinity()};
    }
    tracer.intersect8(rays, packet, hits);
    for (int i = 0; i < packet; ++i)
      if (!hits[i].missed() && !hits[i].frontFace)
        backfaces.push_back({std::max(0.0f, hits[i].distance - behind), first + i});
  }
  if (raysTraced) *raysTraced += count;
  return backfaces;
}

float backfaceRatio(std::size_t backfaces, std::size_t rays) {
  return rays == 0 ? 0.0f : float(backfaces) / float(rays);
}

bool blockedBetween(const RayTracer& tracer, const Eigen::Vector3f& origin, const Eigen::Vector3f& direction,
                    float from, float to, std::int64_t* raysTraced) {
  const Ray ray{origin, direction, from, to};
  bool blocked = false;
  tracer.occluded(&ray, 1, &blocked);
  if (raysTraced) ++*raysTraced;
  return blocked;
}

}  // namespace

std::vector<Eigen::Vector3f> validityDirections(const ValidityOptions& options) {
  std::vector<Eigen::Vector3f> directions;
  for (const Eigen::Vector3d& d : sphericalFibonacci(options.rays).directions) directions.push_back(d.cast<float>());
  return directions;
}

ProbePlacement placeProbe(const RayTracer& tracer, const Eigen::Vector3f& gridPosition, float spacing,
                          const std::vector<Eigen::Vector3f>& directions, const ValidityOptions& options,
                          std::int64_t* raysTraced) {
  ProbePlacement placement;
  const float behind = startBehind(gridPosition, spacing);
  std::vector<BackfaceHit> backfaces = traceBackfaces(tracer, gridPosition, behind, directions, raysTraced);
  placement.backfaceRatio = backfaceRatio(backfaces.size(), directions.size());
  if (placement.backfaceRatio <= options.maxBackfaceRatio) return placement;

  placement.state = ProbeState::Invalid;
  // Ties go to the lower direction index, so the choice is the same on every machine.
  std::sort(backfaces.begin(), backfaces.end(), [](const BackfaceHit& a, const BackfaceHit& b) {
    return std::tie(a.distance, a.direction) < std::tie(b.distance, b.direction);
  });
  const float maxOffset = options.maxOffsetFraction * spacing;
  const float coordinateScale = gridPosition.cwiseAbs().maxCoeff();
  int retests = 0;
  for (const BackfaceHit& hit : backfaces) {
    const float margin = std::max(kMarginFraction * spacing, kMarginSteps * std::numeric_limits<float>::epsilon() *
                                                                 std::max(coordinateScale, hit.distance));
    const float distance = hit.distance + margin;
    // Written so that a NaN spacing stops here too; distance only grows along the sorted hits.
    if (!(distance <= maxOffset) || retests == kMaxCandidates) break;
    const Eigen::Vector3f& direction = directions[hit.direction];
    // The ray is clear up to the back face it hit; the margin beyond it must be clear as well,
    // or the move would pass through a second surface (a wall's other side, a thin panel).
    if (blockedBetween(tracer, gridPosition, direction, hit.distance + kCrossedSurfaceSkip * margin, distance,
                       raysTraced))
      continue;
    ++retests;
    const Eigen::Vector3f offset = distance * direction;
    const std::vector<BackfaceHit> there =
        traceBackfaces(tracer, gridPosition + offset, startBehind(gridPosition + offset, spacing), directions, raysTraced);
    if (backfaceRatio(there.size(), directions.size()) <= options.maxBackfaceRatio) {
      placement.offset = offset;
      placement.state = ProbeState::Relocated;
      return placement;
    }
  }
  return placement;
}

void fillInvalidProbes(const ProbeGrid& grid, const std::vector<ProbeState>& states, int valuesPerProbe,
                       std::vector<float>& values) {
  const std::int64_t probes = grid.probeCount();
  if (valuesPerProbe < 0 || std::int64_t(states.size()) != probes ||
      std::int64_t(values.size()) != probes * valuesPerProbe)
    throw std::invalid_argument("fillInvalidProbes: states and values do not match the grid");
  const std::size_t width = std::size_t(valuesPerProbe);
  const std::int64_t dx = grid.dims.x(), dy = grid.dims.y(), dz = grid.dims.z();
  // Face neighbours are the nearest valid data, and every probe of the grid is reached through
  // them; the 26 would add corners √3 spacings away without reaching anything new.
  const auto forEachFaceNeighbour = [&](std::int64_t p, auto&& visit) {
    const std::int64_t i = p % dx, j = (p / dx) % dy, k = p / (dx * dy);
    if (i > 0) visit(p - 1);
    if (i + 1 < dx) visit(p + 1);
    if (j > 0) visit(p - dx);
    if (j + 1 < dy) visit(p + dx);
    if (k > 0) visit(p - dx * dy);
    if (k + 1 < dz) visit(p + dx * dy);
  };

  // Known probes can feed their neighbours; a queued one is filled by the current pass and
  // becomes known only after it, so a pass reads nothing it wrote itself.
  enum Mark : std::uint8_t { kUnknown, kQueued, kKnown };
  std::vector<Mark> marks(std::size_t(probes), kKnown);
  for (std::int64_t p = 0; p < probes; ++p)
    if (states[p] == ProbeState::Invalid) {
      marks[p] = kUnknown;
      std::fill_n(values.begin() + p * valuesPerProbe, width, 0.0f);
    }

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

}  // namespace baker
