#include "validate/ValidationReport.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace baker {
namespace {

// How many validity changes a check's details spell out; the JSON lists them all.
constexpr std::size_t kListedChanges = 20;

nlohmann::json triple(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

std::string positionText(const Eigen::Vector3d& v) { return fmt::format("({:.4g}, {:.4g}, {:.4g})", v.x(), v.y(), v.z()); }

// The keys both modes share, so that one CI script reads either report.
nlohmann::json commonJson(const std::string& mode, const std::string& reference, const std::string& candidate,
                          const RelativeErrors& errors, double tolerance, std::int64_t compared, std::int64_t outside) {
  return {{"mode", mode},
          {"reference", reference},
          {"new", candidate},
          {"error_definition", kRelativeErrorDefinition},
          {"normals", comparisonNormals().size()},
          {"floor", errors.floor},
          {"tolerance", tolerance},
          {"max_relative_error", errors.max},
          {"mean_relative_error", errors.mean},
          {"p99_relative_error", errors.p99},
          {"level", errors.level},
          {"error_of_level", errors.level > 0.0 ? nlohmann::json{{"mean", errors.levelMean}, {"p99", errors.levelP99},
                                                                 {"max", errors.levelMax}}
                                                : nlohmann::json(nullptr)},
          {"probes_compared", compared},
          {"probes_outside_new_grid", outside}};
}

nlohmann::json differencesJson(const std::vector<MetadataDifference>& differences) {
  nlohmann::json out = nlohmann::json::array();
  for (const MetadataDifference& d : differences)
    out.push_back({{"field", d.field}, {"reference", d.reference}, {"new", d.candidate}});
  return out;
}

ValidationCheck irradianceCheck(const RelativeErrors& errors, double tolerance, const std::string& worstProbe,
                                const std::string& details) {
  ValidationCheck c;
  c.name = "irradiance within tolerance";
  c.passed = errors.max <= tolerance;
  c.message = fmt::format("max relative error {:.4g} {} tolerance {:.4g} (mean {:.4g}, 99th percentile {:.4g}){}",
                          errors.max, c.passed ? "<=" : ">", tolerance, errors.mean, errors.p99,
                          worstProbe.empty() ? "" : ", worst at " + worstProbe);
  c.details = details;
  return c;
}

ValidationCheck metadataCheck(const std::string& name, const std::vector<MetadataDifference>& differences) {
  ValidationCheck c;
  c.name = name;
  c.message = differences.empty() ? "no differences"
                                  : fmt::format("{} difference(s), reported only: they do not fail validation",
                                                differences.size());
  for (const MetadataDifference& d : differences)
    c.details += fmt::format("{}: reference \"{}\", new \"{}\"\n", d.field, d.reference, d.candidate);
  return c;
}

// Adaptive volumes on the same grids must place the same probes: where geometry moved, an engine
// reads other probes there.
ValidationCheck placementCheck(const VolumeComparison::Placement& placement) {
  ValidationCheck c;
  c.name = "placement unchanged";
  c.passed = placement.referenceOnly == 0 && placement.newOnly == 0;
  c.message = c.passed ? "every level holds the same probes"
                       : fmt::format("{} probe(s) held only by the reference, {} only by the new volume (compared "
                                     "where the new volume does not hold them as it reads there)",
                                     placement.referenceOnly, placement.newOnly);
  return c;
}

// "level L " before a probe of an adaptive volume's level; nothing for a uniform one.
std::string levelText(const VolumeComparison& comparison, int level) {
  return comparison.adaptive ? fmt::format("level {} ", level) : "";
}

// The verdict and the checks go into the JSON last, once every check is known.
void recordChecks(ValidationReport& report) {
  nlohmann::json checks = nlohmann::json::array();
  for (const ValidationCheck& c : report.checks)
    checks.push_back({{"name", c.name}, {"passed", c.passed}, {"skipped", c.skipped}, {"message", c.message}});
  report.json["checks"] = checks;
  report.json["passed"] = report.passed();
}

std::string xmlEscaped(const std::string& text) {
  std::string out;
  for (char ch : text) {
    switch (ch) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default: out += ch;
    }
  }
  return out;
}

}  // namespace

bool ValidationReport::passed() const {
  return std::all_of(checks.begin(), checks.end(), [](const ValidationCheck& c) { return c.passed; });
}

ValidationReport volumeValidationReport(const VolumeComparison& comparison, const std::string& referencePath,
                                        const std::string& newPath, double tolerance) {
  ValidationReport report;
  nlohmann::json& j = report.json;
  j = commonJson("volume", referencePath, newPath, comparison.errors, tolerance, comparison.probesCompared,
                 comparison.probesOutside);
  j["grids_match"] = comparison.gridsMatch;

  nlohmann::json worst = nlohmann::json::array();
  std::string worstDetails;
  for (const ComparedProbe& p : comparison.worst) {
    worst.push_back({{"adaptive_level", p.level},
                     {"index", {p.index.x(), p.index.y(), p.index.z()}},
                     {"position", triple(p.position)},
                     {"relative_error", p.relativeError},
                     {"max_abs_error", p.maxAbsoluteError},
                     {"reference_mean_irradiance", p.referenceMean}});
    worstDetails += fmt::format("{}probe [{}, {}, {}] at {}: relative error {:.4g} (max |dE| {:.4g}, reference mean E {:.4g})\n",
                                levelText(comparison, p.level), p.index.x(), p.index.y(), p.index.z(),
                                positionText(p.position), p.relativeError, p.maxAbsoluteError, p.referenceMean);
  }
  j["worst_probes"] = worst;

  nlohmann::json changes = nlohmann::json::array();
  std::string changeDetails;
  for (const ValidityChange& v : comparison.validityChanges) {
    changes.push_back({{"adaptive_level", v.level},
                       {"index", {v.index.x(), v.index.y(), v.index.z()}},
                       {"position", triple(v.position)},
                       {"reference", probeStateName(v.reference)},
                       {"new", probeStateName(v.candidate)}});
    if (changes.size() <= kListedChanges)
      changeDetails += fmt::format("{}probe [{}, {}, {}] at {}: {} -> {}\n", levelText(comparison, v.level), v.index.x(),
                                   v.index.y(), v.index.z(), positionText(v.position), probeStateName(v.reference),
                                   probeStateName(v.candidate));
  }
  if (changes.size() > kListedChanges) changeDetails += fmt::format("... and {} more\n", changes.size() - kListedChanges);
  j["validity_compared"] = comparison.validityCompared;
  j["validity_changes"] = changes;
  j["sky_visibility_max_abs_difference"] = comparison.skyVisibilityMaxDifference
                                               ? nlohmann::json(*comparison.skyVisibilityMaxDifference)
                                               : nlohmann::json(nullptr);
  j["metadata_differences"] = differencesJson(comparison.metadataDifferences);

  std::string worstProbe;
  if (!comparison.worst.empty()) {
    const ComparedProbe& w = comparison.worst.front();
    worstProbe = fmt::format("{}probe [{}, {}, {}] {}", levelText(comparison, w.level), w.index.x(), w.index.y(),
                             w.index.z(), positionText(w.position));
  }
  report.checks.push_back(irradianceCheck(comparison.errors, tolerance, worstProbe, worstDetails));

  ValidationCheck validity;
  validity.name = "validity unchanged";
  if (!comparison.validityCompared) {
    validity.skipped = true;
    validity.message = "not compared: the grids differ, so probes do not correspond one to one";
  } else {
    validity.passed = comparison.validityChanges.empty();
    validity.message = validity.passed ? "every probe kept its probe_state"
                                       : fmt::format("{} probe(s) changed probe_state", comparison.validityChanges.size());
    validity.details = changeDetails;
  }
  report.checks.push_back(validity);
  if (comparison.placement) report.checks.push_back(placementCheck(*comparison.placement));
  j["placement_changes"] = comparison.placement ? nlohmann::json{{"reference_only", comparison.placement->referenceOnly},
                                                                  {"new_only", comparison.placement->newOnly}}
                                                : nlohmann::json(nullptr);
  report.checks.push_back(metadataCheck("metadata", comparison.metadataDifferences));

  recordChecks(report);
  return report;
}

ValidationReport referenceValidationReport(const ReferenceComparison& comparison, const std::string& referenceDirectory,
                                           const std::string& volumePath, double tolerance) {
  ValidationReport report;
  nlohmann::json& j = report.json;
  j = commonJson("reference", referenceDirectory, volumePath, comparison.errors, tolerance, comparison.probesCompared,
                 comparison.probesOutside);
  j["note"] =
      "reference panoramas contain no punctual light seen directly: bake the volume with --no direct-punctual";

  nlohmann::json worst = nlohmann::json::array();
  std::string worstDetails;
  for (const ReferenceProbeError& p : comparison.worst) {
    worst.push_back({{"index", p.probe.index},
                     {"file", p.probe.file},
                     {"position", triple(p.probe.position)},
                     {"relative_error", p.relativeError},
                     {"max_abs_error", p.maxAbsoluteError},
                     {"reference_mean_irradiance", p.referenceMean}});
    worstDetails += fmt::format("reference probe {} at {}: relative error {:.4g} (max |dE| {:.4g}, reference mean E {:.4g})\n",
                                p.probe.index, positionText(p.probe.position), p.relativeError, p.maxAbsoluteError,
                                p.referenceMean);
  }
  j["worst_probes"] = worst;
  j["validity_compared"] = false;
  j["validity_changes"] = nlohmann::json::array();
  j["sky_visibility_max_abs_difference"] = nullptr;
  j["metadata_differences"] = differencesJson(comparison.settingDifferences);

  std::string worstProbe;
  if (!comparison.worst.empty())
    worstProbe = fmt::format("reference probe {} {}", comparison.worst.front().probe.index,
                             positionText(comparison.worst.front().probe.position));
  report.checks.push_back(irradianceCheck(comparison.errors, tolerance, worstProbe, worstDetails));
  report.checks.push_back(metadataCheck("bake settings", comparison.settingDifferences));

  recordChecks(report);
  return report;
}

std::string junitXml(const ValidationReport& report) {
  std::size_t failures = 0, skipped = 0;
  for (const ValidationCheck& c : report.checks) {
    failures += c.passed ? 0 : 1;
    skipped += c.skipped ? 1 : 0;
  }
  std::string xml = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  xml += fmt::format("<testsuite name=\"baker validate\" tests=\"{}\" failures=\"{}\" errors=\"0\" skipped=\"{}\">\n",
                     report.checks.size(), failures, skipped);
  xml += "  <properties>\n";
  for (const char* key : {"mode", "reference", "new", "tolerance", "error_definition"}) {
    const nlohmann::json& value = report.json.at(key);
    xml += fmt::format("    <property name=\"{}\" value=\"{}\"/>\n", key,
                       xmlEscaped(value.is_string() ? value.get<std::string>() : value.dump()));
  }
  xml += "  </properties>\n";
  for (const ValidationCheck& c : report.checks) {
    xml += fmt::format("  <testcase classname=\"baker validate\" name=\"{}\">\n", xmlEscaped(c.name));
    if (!c.passed)
      xml += fmt::format("    <failure message=\"{}\" type=\"{}\">{}</failure>\n", xmlEscaped(c.message),
                         xmlEscaped(c.name), xmlEscaped(c.details));
    else if (c.skipped)
      xml += fmt::format("    <skipped message=\"{}\"/>\n", xmlEscaped(c.message));
    else
      xml += fmt::format("    <system-out>{}\n{}</system-out>\n", xmlEscaped(c.message), xmlEscaped(c.details));
    xml += "  </testcase>\n";
  }
  xml += "</testsuite>\n";
  return xml;
}

std::string textSummary(const ValidationReport& report) {
  const nlohmann::json& j = report.json;
  std::string text = fmt::format("{} against {}: {} probes compared", j["new"].get<std::string>(),
                                 j["reference"].get<std::string>(), j["probes_compared"].get<std::int64_t>());
  if (j["probes_outside_new_grid"].get<std::int64_t>() > 0)
    text += fmt::format(" ({} outside the new volume's grid, skipped)", j["probes_outside_new_grid"].get<std::int64_t>());
  if (j.contains("grids_match") && !j["grids_match"].get<bool>()) text += ", new volume sampled trilinearly";
  if (j.contains("placement_changes") && !j["placement_changes"].is_null() &&
      j["placement_changes"]["reference_only"].get<std::int64_t>() > 0)
    text += ", new volume sampled where it does not hold the reference's probe";
  text += "\n";
  text += fmt::format("{}; floor {:.4g}\n", kRelativeErrorDefinition, j["floor"].get<double>());
  if (j.contains("note")) text += fmt::format("note: {}\n", j["note"].get<std::string>());
  if (!j["sky_visibility_max_abs_difference"].is_null())
    text += fmt::format("sky visibility: max |dV| {:.4g}\n", j["sky_visibility_max_abs_difference"].get<double>());
  for (const ValidationCheck& c : report.checks) {
    text += fmt::format("{}: {}: {}\n", c.skipped ? "SKIP" : c.passed ? "PASS" : "FAIL", c.name, c.message);
    std::string details = c.details;
    for (std::size_t start = 0; start < details.size();) {
      const std::size_t end = std::min(details.find('\n', start), details.size());
      text += "  " + details.substr(start, end - start) + "\n";
      start = end + 1;
    }
  }
  text += report.passed() ? "passed\n" : "FAILED\n";
  return text;
}

}  // namespace baker
