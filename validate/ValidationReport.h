#pragma once
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "validate/ReferenceComparison.h"
#include "validate/VolumeComparison.h"

namespace baker {

// One pass/fail question a CI system shows as a test case. A skipped check could not be asked
// (validity when the grids differ); an informational one lists what differs and never fails.
struct ValidationCheck {
  std::string name;
  bool passed = true;
  bool skipped = false;
  std::string message;  // one line
  std::string details;  // further lines: the probes or fields concerned
};

// What `baker validate` found, as the JSON it writes with --report and --json (keys documented in
// cli/ValidateCommand.h) and the checks it turns into JUnit XML and the text summary.
struct ValidationReport {
  nlohmann::json json;
  std::vector<ValidationCheck> checks;
  bool passed() const;
};

// Checks: irradiance within tolerance, validity unchanged, metadata (informational).
ValidationReport volumeValidationReport(const VolumeComparison& comparison, const std::string& referencePath,
                                        const std::string& newPath, double tolerance);
// Checks: irradiance within tolerance, bake settings (informational).
ValidationReport referenceValidationReport(const ReferenceComparison& comparison, const std::string& referenceDirectory,
                                           const std::string& volumePath, double tolerance);

// One <testsuite name="baker validate"> with a <testcase> per check, <failure> or <skipped> with
// the message, and the details as the element's text.
std::string junitXml(const ValidationReport& report);
// A few lines for a person at a terminal.
std::string textSummary(const ValidationReport& report);

}  // namespace baker
