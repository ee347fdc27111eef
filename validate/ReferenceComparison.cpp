#include "validate/ReferenceComparison.h"

#include <fmt/format.h>

#include "formats/VolumeReconstruction.h"

namespace baker {
namespace {

std::vector<MetadataDifference> settingDifferences(const Volume& volume, const ReferenceSet& set) {
  std::vector<MetadataDifference> out;
  const auto punctual = volume.settings.find("effect.direct-punctual");
  if (punctual != volume.settings.end() && punctual->second == "on")
    out.push_back({"setting.effect.direct-punctual", "off (panoramas hold no punctual light seen directly)", "on"});
  // reference_probe.py --bounces n allows n + 1 diffuse reflections, baker --bounces B allows B.
  const auto bounces = volume.settings.find("bounces");
  if (set.settings.is_object() && set.settings.contains("bounces") && set.settings["bounces"].is_number_integer() &&
      bounces != volume.settings.end()) {
    const std::string expected = std::to_string(set.settings["bounces"].get<int>() + 1);
    if (bounces->second != expected)
      out.push_back({"setting.bounces", fmt::format("{} (reference_probe.py --bounces {})", expected,
                                                    set.settings["bounces"].get<int>()),
                     bounces->second});
  }
  return out;
}

}  // namespace

ReferenceComparison compareWithReference(const AdaptiveVolume& levels, const ReferenceSet& set, std::size_t worstCount) {
  const Volume& volume = levels.coarsest();
  const VolumeReconstruction reading(volume);
  const std::vector<Eigen::Vector3d>& normals = comparisonNormals();
  ReferenceComparison result;
  result.settingDifferences = settingDifferences(volume, set);
  std::vector<ProbeDifference> differences;
  std::vector<ReferenceProbeError> probes;
  std::vector<Eigen::Vector3d> eVolume(normals.size());
  std::vector<float> coefficients(std::size_t(volume.coefficientsPerProbe)), visibility(std::size_t(volume.visibilityPerProbe));
  for (const ReferenceProbe& probe : set.probes) {
    if (!insideCells(volume.grid, probe.position)) {
      ++result.probesOutside;
      continue;
    }
    const std::vector<Eigen::Vector3d> eReference = panoramaIrradiance(readRgbImage(probe.file), normals);
    sampleLevels(levels.levels, int(levels.levels.size()), probe.position, coefficients.data(), visibility.data());
    for (std::size_t n = 0; n < normals.size(); ++n)
      eVolume[n] = reading.irradiance(coefficients.data(), normals[n]).cast<double>();
    const ProbeDifference d = probeDifference(eReference, eVolume);
    differences.push_back(d);
    probes.push_back({probe, 0.0, d.maxAbsolute, d.referenceMean});
  }
  result.probesCompared = std::int64_t(probes.size());
  result.errors = relativeErrors(differences);
  result.worst = worstProbes(probes, result.errors.perProbe, worstCount);
  return result;
}

}  // namespace baker
