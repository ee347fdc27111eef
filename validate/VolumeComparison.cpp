#include "validate/VolumeComparison.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "common/Error.h"
#include "formats/VolumeReconstruction.h"
#include "formats/VolumeSampler.h"

namespace baker {
namespace {

// Files without probe_state hold only probes baked where the grid puts them.
ProbeState stateOf(const Volume& v, std::int64_t p) { return v.states.empty() ? ProbeState::Valid : v.states[p]; }

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

VolumeComparison compareVolumes(const Volume& reference, const Volume& candidateAsStored, std::size_t worstCount,
                                const RunTimeSky& runTimeSky) {
  const std::optional<Volume> rest =
      runTimeSky.sky ? std::optional(lightThatIsNotTheSkys(candidateAsStored, runTimeSky.name)) : std::nullopt;
  const Volume& candidate = rest ? *rest : candidateAsStored;
  const VolumeReconstruction referenceReading(reference), candidateReading(candidate);
  const std::vector<Eigen::Vector3d>& normals = comparisonNormals();
  const ProbeGrid& g = reference.grid;
  const bool visibility = reference.visibilityPerProbe > 0 && candidate.visibilityPerProbe > 0;

  VolumeComparison result;
  result.gridsMatch = sameGrid(g, candidate.grid);
  result.validityCompared = result.gridsMatch;
  result.metadataDifferences = metadataDifferences(reference, candidate);
  if (visibility) result.skyVisibilityMaxDifference = 0.0;

  std::vector<ProbeDifference> differences;
  std::vector<ComparedProbe> probes;
  std::vector<Eigen::Vector3d> eReference(normals.size()), eCandidate(normals.size());
  for (int k = 0; k < g.dims.z(); ++k)
    for (int j = 0; j < g.dims.y(); ++j)
      for (int i = 0; i < g.dims.x(); ++i) {
        const std::int64_t p = g.linearIndex(i, j, k);
        const Eigen::Vector3d position = g.position(i, j, k);
        if (!result.gridsMatch && !insideCells(candidate.grid, position)) {
          ++result.probesOutside;
          continue;
        }
        VolumeSample sample;
        if (!result.gridsMatch) sample = sampleVolume(candidate, position);
        const float* coefficients = result.gridsMatch ? candidate.probe(p) : sample.coefficients.data();
        const float* candidateVisibility =
            result.gridsMatch ? candidate.visibility.data() + p * candidate.visibilityPerProbe : sample.visibility.data();
        for (std::size_t n = 0; n < normals.size(); ++n) {
          eReference[n] = referenceReading.irradiance(reference.probe(p), normals[n]).cast<double>();
          eCandidate[n] = (runTimeSky.sky ? candidateReading.relitIrradiance(coefficients, candidateVisibility, normals[n],
                                                                             *runTimeSky.sky)
                                          : candidateReading.irradiance(coefficients, normals[n]))
                              .cast<double>();
          if (visibility) {
            const double vr = referenceReading.skyVisibility(
                reference.visibility.data() + p * reference.visibilityPerProbe, normals[n]);
            const double vc = candidateReading.skyVisibility(candidateVisibility, normals[n]);
            result.skyVisibilityMaxDifference = std::max(*result.skyVisibilityMaxDifference, std::abs(vc - vr));
          }
        }
        const ProbeDifference d = probeDifference(eReference, eCandidate);
        differences.push_back(d);
        probes.push_back({Eigen::Vector3i(i, j, k), position, 0.0, d.maxAbsolute, d.referenceMean});
        if (result.validityCompared && stateOf(reference, p) != stateOf(candidate, p))
          result.validityChanges.push_back(
              {Eigen::Vector3i(i, j, k), position, stateOf(reference, p), stateOf(candidate, p)});
      }

  result.probesCompared = std::int64_t(probes.size());
  result.errors = relativeErrors(differences);
  result.worst = worstProbes(probes, result.errors.perProbe, worstCount);
  return result;
}

}  // namespace baker
