#include "validate/IrradianceError.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace baker {

const char* const kRelativeErrorDefinition =
    "relative error of a probe = max over the 26 normals (cube faces, edges and corners) and RGB of "
    "|E_new(n) - E_ref(n)| / max(m, floor), m = mean over the normals of the reference's (R+G+B)/3, "
    "floor = 1e-3 x the mean m of all compared probes";

const std::vector<Eigen::Vector3d>& comparisonNormals() {
  static const std::vector<Eigen::Vector3d> normals = [] {
    std::vector<Eigen::Vector3d> result;
    for (int x = -1; x <= 1; ++x)
      for (int y = -1; y <= 1; ++y)
        for (int z = -1; z <= 1; ++z)
          if (x != 0 || y != 0 || z != 0) result.push_back(Eigen::Vector3d(x, y, z).normalized());
    return result;
  }();
  return normals;
}

ProbeDifference probeDifference(const std::vector<Eigen::Vector3d>& reference,
                                const std::vector<Eigen::Vector3d>& candidate) {
  ProbeDifference d;
  for (std::size_t n = 0; n < reference.size(); ++n) {
    d.maxAbsolute = std::max(d.maxAbsolute, (candidate[n] - reference[n]).cwiseAbs().maxCoeff());
    d.referenceMean += reference[n].mean();
    d.candidateMean += candidate[n].mean();
  }
  if (!reference.empty()) {
    d.referenceMean /= double(reference.size());
    d.candidateMean /= double(reference.size());
  }
  return d;
}

RelativeErrors relativeErrors(const std::vector<ProbeDifference>& differences) {
  RelativeErrors r;
  if (differences.empty()) return r;
  double referenceLevel = 0.0, candidateLevel = 0.0;
  for (const ProbeDifference& d : differences) {
    referenceLevel += d.referenceMean;
    candidateLevel += d.candidateMean;
  }
  r.floor = 1e-3 * std::max(referenceLevel, 0.0) / double(differences.size());
  if (r.floor == 0.0) r.floor = 1e-3 * std::abs(candidateLevel) / double(differences.size());
  r.perProbe.reserve(differences.size());
  for (const ProbeDifference& d : differences) {
    const double scale = std::max(d.referenceMean, r.floor);
    // Both sides black on average leave no scale at all: the difference is reported as it is.
    r.perProbe.push_back(scale > 0.0 ? d.maxAbsolute / scale : d.maxAbsolute);
  }
  std::vector<double> sorted = r.perProbe;
  std::sort(sorted.begin(), sorted.end());
  r.max = sorted.back();
  r.mean = std::accumulate(sorted.begin(), sorted.end(), 0.0) / double(sorted.size());
  const std::size_t rank = std::size_t(std::ceil(0.99 * double(sorted.size())));
  r.p99 = sorted[std::max<std::size_t>(rank, 1) - 1];
  r.level = std::max(referenceLevel, 0.0) / double(differences.size());
  if (r.level > 0.0) {
    std::vector<double> ofLevel;
    for (const ProbeDifference& d : differences) ofLevel.push_back(d.maxAbsolute / r.level);
    std::sort(ofLevel.begin(), ofLevel.end());
    r.levelMax = ofLevel.back();
    r.levelMean = std::accumulate(ofLevel.begin(), ofLevel.end(), 0.0) / double(ofLevel.size());
    r.levelP99 = ofLevel[std::max<std::size_t>(rank, 1) - 1];
  }
  return r;
}

std::vector<std::size_t> largestErrors(const std::vector<double>& errors, std::size_t count) {
  std::vector<std::size_t> order(errors.size());
  std::iota(order.begin(), order.end(), std::size_t(0));
  count = std::min(count, order.size());
  std::partial_sort(order.begin(), order.begin() + count, order.end(), [&](std::size_t a, std::size_t b) {
    return errors[a] > errors[b] || (errors[a] == errors[b] && a < b);
  });
  order.resize(count);
  return order;
}

}  // namespace baker
