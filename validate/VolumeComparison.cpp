#include "validate/VolumeComparison.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "common/Error.h"
#include "formats/VolumeReconstruction.h"

namespace baker {
namespace {

// Files without probe_state hold only probes baked where the grid puts them.
ProbeState stateOf(const Volume& v, std::int64_t row) { return v.states.empty() ? ProbeState::Valid : v.states[std::size_t(row)]; }

std::string vectorText(const Eigen::Vector3d& v) { return fmt::format("{},{},{}", v.x(), v.y(), v.z()); }

std::vector<MetadataDifference> metadataDifferences(const Volume& a, const Volume& b) {
  std::vector<MetadataDifference> out;
  if (a.basisName != b.basisName) out.push_back({"basis", a.basisName, b.basisName});
  if (a.grid.dims != b.grid.dims)
    out.push_back({"dims", vectorText(a.grid.dims.cast<double>()), vectorText(b.grid.dims.cast<double>())});
  if (a.grid.origin != b.grid.origin) out.push_back({"origin", vectorText(a.grid.origin), vectorText(b.grid.origin)});
  if (a.grid.spacing != b.grid.spacing)
    out.push_back({"spacing", fmt::format("{}", a.grid.spacing), fmt::format("{}", b.grid.spacing)});
  auto ia = a.settings.begin(), ib = b.settings.begin();
  // Both maps are sorted by key: one merge pass finds keys on one side only and changed values.
  while (ia != a.settings.end() || ib != b.settings.end()) {
    if (ib == b.settings.end() || (ia != a.settings.end() && ia->first < ib->first)) {
      out.push_back({"setting." + ia->first, ia->second, ""});
      ++ia;
    } else if (ia == a.settings.end() || ib->first < ia->first) {
      out.push_back({"setting." + ib->first, "", ib->second});
      ++ib;
    } else {
      if (ia->second != ib->second) out.push_back({"setting." + ia->first, ia->second, ib->second});
      ++ia;
      ++ib;
    }
  }
  return out;
}

bool sameLevels(const AdaptiveVolume& a, const AdaptiveVolume& b) {
  if (a.levels.size() != b.levels.size()) return false;
  for (std::size_t level = 0; level < a.levels.size(); ++level)
    if (!sameGrid(a.levels[level].grid, b.levels[level].grid)) return false;
  return true;
}

// The probes `volume` holds that `other` (on the same grids) does not, over every level.
std::int64_t probesOnlyIn(const AdaptiveVolume& volume, const AdaptiveVolume& other) {
  std::int64_t count = 0;
  for (std::size_t level = 0; level < volume.levels.size(); ++level) {
    const Volume& v = volume.levels[level];
    for (std::int64_t row = 0; row < v.rows.count(v.grid); ++row)
      count += other.levels[level].rowOf(v.rows.probeAt(v.grid, row)) < 0;
  }
  return count;
}

// How the new volume reads at one reference probe: its own probe there, or sampled.
struct CandidateReading {
  const float* coefficients;
  const float* visibility;
  std::int64_t row;  // its row at the reference probe's level when it holds that probe, else -1
};

}  // namespace

bool sameGrid(const ProbeGrid& grid, const ProbeGrid& other) {
  const double slack = 1e-9 * std::max(grid.spacing, other.spacing);
  return grid.dims == other.dims && std::abs(grid.spacing - other.spacing) <= slack &&
         (grid.origin - other.origin).cwiseAbs().maxCoeff() <= slack;
}

bool insideCells(const ProbeGrid& grid, const Eigen::Vector3d& position) {
  const Eigen::Vector3d cell = (position - grid.origin) / grid.spacing;
  const double slack = 1e-9;
  for (int a = 0; a < 3; ++a)
    if (cell[a] < -0.5 - slack || cell[a] > grid.dims[a] - 0.5 + slack) return false;
  return true;
}

Volume lightThatIsNotTheSkys(const Volume& volume, const std::string& name) {
  if (!volume.keepsSkyDirect)
    throw InputError(fmt::format("{}: holds no sky_direct grids, which relighting at run time subtracts (bake it again "
                                 "with this version, under a sky)",
                                 name));
  Volume rest = volume;
  for (std::size_t i = 0; i < rest.coefficients.size(); ++i) rest.coefficients[i] -= rest.skyDirect[i];
  return rest;
}

VolumeComparison compareVolumes(const AdaptiveVolume& reference, const AdaptiveVolume& candidateAsStored,
                                std::size_t worstCount, const RunTimeSky& runTimeSky) {
  AdaptiveVolume rest;
  if (runTimeSky.sky) {
    rest.marginCells = candidateAsStored.marginCells;
    for (const Volume& level : candidateAsStored.levels) rest.levels.push_back(lightThatIsNotTheSkys(level, runTimeSky.name));
  }
  const AdaptiveVolume& candidate = runTimeSky.sky ? rest : candidateAsStored;
  const VolumeReconstruction referenceReading(reference.coarsest()), candidateReading(candidate.coarsest());
  const std::vector<Eigen::Vector3d>& normals = comparisonNormals();
  const bool visibility = reference.coarsest().visibilityPerProbe > 0 && candidate.coarsest().visibilityPerProbe > 0;
  const int candidateLevels = int(candidate.levels.size());

  VolumeComparison result;
  result.adaptive = reference.levels.size() > 1;
  result.gridsMatch = sameLevels(reference, candidate);
  result.validityCompared = result.gridsMatch;
  result.metadataDifferences = metadataDifferences(reference.coarsest(), candidate.coarsest());
  if (reference.levels.size() != candidate.levels.size())
    result.metadataDifferences.push_back(
        {"levels", std::to_string(reference.levels.size()), std::to_string(candidate.levels.size())});
  if (result.gridsMatch && (reference.levels.size() > 1 || candidate.levels.size() > 1))
    result.placement = VolumeComparison::Placement{probesOnlyIn(reference, candidate), probesOnlyIn(candidate, reference)};
  if (visibility) result.skyVisibilityMaxDifference = 0.0;

  std::vector<ProbeDifference> differences;
  std::vector<ComparedProbe> probes;
  std::vector<Eigen::Vector3d> eReference(normals.size()), eCandidate(normals.size());
  std::vector<float> sampledCoefficients(std::size_t(candidate.coarsest().coefficientsPerProbe));
  std::vector<float> sampledVisibility(std::size_t(candidate.coarsest().visibilityPerProbe));
  for (int level = 0; level < int(reference.levels.size()); ++level) {
    const Volume& r = reference.levels[std::size_t(level)];
    for (std::int64_t referenceRow = 0; referenceRow < r.rows.count(r.grid); ++referenceRow) {
      const std::int64_t p = r.rows.probeAt(r.grid, referenceRow);
      const Eigen::Vector3i index = r.grid.indexOf(p);
      const Eigen::Vector3d position = r.grid.position(p);
      CandidateReading c{nullptr, nullptr, result.gridsMatch ? candidate.levels[std::size_t(level)].rowOf(p) : -1};
      if (c.row >= 0) {
        const Volume& v = candidate.levels[std::size_t(level)];
        c.coefficients = v.coefficients.data() + c.row * v.coefficientsPerProbe;
        c.visibility = v.visibility.data() + c.row * v.visibilityPerProbe;
      } else {
        if (!insideCells(candidate.coarsest().grid, position)) {
          ++result.probesOutside;
          continue;
        }
        sampleLevels(candidate.levels, candidateLevels, position, sampledCoefficients.data(), sampledVisibility.data());
        c.coefficients = sampledCoefficients.data();
        c.visibility = sampledVisibility.data();
      }
      const float* referenceVisibility = r.visibility.data() + referenceRow * r.visibilityPerProbe;
      for (std::size_t n = 0; n < normals.size(); ++n) {
        eReference[n] = referenceReading.irradiance(r.coefficients.data() + referenceRow * r.coefficientsPerProbe,
                                                    normals[n]).cast<double>();
        eCandidate[n] = (runTimeSky.sky ? candidateReading.relitIrradiance(c.coefficients, c.visibility, normals[n],
                                                                           *runTimeSky.sky)
                                        : candidateReading.irradiance(c.coefficients, normals[n]))
                            .cast<double>();
        if (visibility) {
          const double vr = referenceReading.skyVisibility(referenceVisibility, normals[n]);
          const double vc = candidateReading.skyVisibility(c.visibility, normals[n]);
          result.skyVisibilityMaxDifference = std::max(*result.skyVisibilityMaxDifference, std::abs(vc - vr));
        }
      }
      const ProbeDifference d = probeDifference(eReference, eCandidate);
      differences.push_back(d);
      probes.push_back({level, index, position, 0.0, d.maxAbsolute, d.referenceMean});
      if (c.row < 0) continue;
      const ProbeState before = stateOf(r, referenceRow), after = stateOf(candidate.levels[std::size_t(level)], c.row);
      if (result.validityCompared && before != after) result.validityChanges.push_back({level, index, position, before, after});
    }
  }

  result.probesCompared = std::int64_t(probes.size());
  result.errors = relativeErrors(differences);
  result.worst = worstProbes(probes, result.errors.perProbe, worstCount);
  return result;
}

}  // namespace baker
