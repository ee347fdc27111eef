#pragma once
#include <Eigen/Core>
#include <cstddef>
#include <vector>

namespace baker {

// How `baker validate` measures the distance between two irradiance fields, one probe at a
// time, in reconstructed irradiance E(n) rather than coefficients, so that volumes of different
// bases (and exact references) compare on the same footing.

// The normals E is compared at: from a cube's centre to its 6 face centres, 12 edge midpoints
// and 8 corners, normalised (26). They cover the sphere evenly enough to catch a lobe that a
// basis puts in the wrong place, and include the axes engines care most about.
const std::vector<Eigen::Vector3d>& comparisonNormals();

// One sentence for help texts and reports.
extern const char* const kRelativeErrorDefinition;

// One probe before normalisation: the largest |E_new − E_ref| over normals and RGB channels,
// and the mean over normals of each side's (R + G + B)/3.
struct ProbeDifference {
  double maxAbsolute = 0.0;
  double referenceMean = 0.0;
  double candidateMean = 0.0;
};

// `reference` and `candidate` hold E (RGB) at each comparison normal, in the same order.
ProbeDifference probeDifference(const std::vector<Eigen::Vector3d>& reference,
                                const std::vector<Eigen::Vector3d>& candidate);

// Every probe's relative error maxAbsolute / max(referenceMean, floor), with floor = 1e-3 × the
// mean referenceMean over all probes, so that dark probes do not turn noise into huge ratios;
// and their maximum, mean and 99th percentile (nearest rank). Only when the reference is black
// everywhere does the floor come from the candidate's mean instead, so that the numbers stay
// finite and still say how far off the candidate is.
struct RelativeErrors {
  std::vector<double> perProbe;
  double floor = 0.0;
  double max = 0.0;
  double mean = 0.0;
  double p99 = 0.0;
  // The same differences as shares of the scene's level (the mean over probes of the reference's
  // mean irradiance), where a dark probe's own mean would magnify them: what a viewer sees.
  double level = 0.0;
  double levelMean = 0.0, levelP99 = 0.0, levelMax = 0.0;
};

RelativeErrors relativeErrors(const std::vector<ProbeDifference>& differences);

// Indices into `errors` of the `count` largest values, largest first (ties: lower index first).
std::vector<std::size_t> largestErrors(const std::vector<double>& errors, std::size_t count);

// The `count` probes with the largest errors, largest first, each with its relativeError set:
// `probes[i]` is the probe whose error is `errors[i]`.
template <typename Probe>
std::vector<Probe> worstProbes(const std::vector<Probe>& probes, const std::vector<double>& errors, std::size_t count) {
  std::vector<Probe> worst;
  for (std::size_t q : largestErrors(errors, count)) {
    worst.push_back(probes[q]);
    worst.back().relativeError = errors[q];
  }
  return worst;
}

}  // namespace baker
