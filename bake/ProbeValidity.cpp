#include "bake/ProbeValidity.h"

#include <algorithm>
#include <limits>
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

}  // namespace baker
