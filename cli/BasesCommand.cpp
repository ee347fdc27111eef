#include "cli/BasesCommand.h"

#include <fmt/format.h>

#include <algorithm>
#include <iostream>
#include <nlohmann/json.hpp>

#include "basis/BasisRegistry.h"
#include "basis/GramOperators.h"
#include "cli/CommandLine.h"
#include "common/Error.h"
#include "validate/BasisEvaluation.h"

namespace baker {
namespace {

constexpr int kMaxReportedOrder = 4;

// Channels of a basis grouped by the function set they share, e.g. {R,G,B} or {Y}, {Co,Cg}.
std::vector<std::vector<int>> channelGroups(const Basis& basis) {
  std::vector<std::vector<int>> groups;
  for (int c = 0; c < 3; ++c) {
    if (c > 0 && &basis.functions(c) == &basis.functions(c - 1)) groups.back().push_back(c);
    else groups.push_back({c});
  }
  return groups;
}

int printListing(bool json) {
  nlohmann::json report = nlohmann::json::array();
  std::string table = fmt::format("{:<14} {:>6} {:>5} {:>9} {:>10} {:>10} {:>10} {:>10}   {:>10} {:>10} {:>10} {:>10}\n",
                                  "basis", "stored", "read", "channels", "cum L1", "cum L2", "cum L3", "cum L4",
                                  "run L1", "run L2", "run L3", "run L4");
  for (const std::string& name : basisNames()) {
    const auto basis = makeBasis(name);
    nlohmann::json sets = nlohmann::json::array();
    for (const std::vector<int>& group : channelGroups(*basis)) {
      std::string channels;
      for (int c : group) channels += channelName(basis->colorSpace(), c);
      const GramOperators ops(basis->functions(group[0]), name);
      const ShReproduction r = ops.shReproduction(kMaxReportedOrder);
      const std::vector<double> cumulative(r.cumulative.begin() + 1, r.cumulative.end());
      const std::vector<double> running(r.runningSum.begin() + 1, r.runningSum.end());
      sets.push_back({{"channels", channels},
                      {"functions", basis->coefficientCount(group[0])},
                      {"gram_condition_number", ops.conditionNumber()},
                      {"sh_reproduction_cumulative", cumulative},
                      {"sh_reproduction_running_sum", running}});
      table += fmt::format("{:<14} {:>6} {:>5} {:>9} {:>10.4g} {:>10.4g} {:>10.4g} {:>10.4g}   {:>10.4g} {:>10.4g} "
                           "{:>10.4g} {:>10.4g}\n",
                           name, basis->totalCoefficients(), basis->coefficientsPerLookup(), channels, cumulative[0],
                           cumulative[1], cumulative[2], cumulative[3], running[0], running[1], running[2],
                           running[3]);
    }
    report.push_back({{"name", name},
                      {"color_space", colorSpaceName(basis->colorSpace())},
                      {"coefficients_stored", basis->totalCoefficients()},
                      {"coefficients_per_lookup", basis->coefficientsPerLookup()},
                      {"function_sets", sets}});
  }
  if (json) {
    nlohmann::json out = {
        {"bases", report},
        {"sh_orders", {1, 2, 3, 4}},
        {"definitions",
         {{"sh_reproduction_cumulative", "||I - P[0:n,0:n]||_F, P = Bsh^T G^-1 Bsh, n = (L+1)^2"},
          {"sh_reproduction_running_sum", "sqrt(sum over k = 0..L of cumulative(k)^2): the paper's Ambient Dice rows"}}}};
    std::cout << out.dump(2) << "\n";
  } else {
    std::cout << table
              << "\nstored: coefficients per probe (RGB); read: coefficients one direction reads.\n"
                 "cum L: ||I - P[0:n,0:n]||_F with P = Bsh^T G^-1 Bsh (paper eq. 9), n = (L+1)^2, for SH up to "
                 "order L\n(the paper's ambient cube row). run L: sqrt(sum of cum(k)^2 for k <= L) (the paper's "
                 "Ambient Dice rows).\n";
  }
  return 0;
}

std::vector<SphereSignal> loadSignals(SignalKind kind, const std::vector<std::string>& inputs,
                                      std::vector<std::string>& skipped) {
  std::vector<SphereSignal> signals;
  for (const std::string& input : inputs) {
    if (kind == SignalKind::Occlusion) {
      for (SphereSignal& s : occlusionSignals(input, skipped)) signals.push_back(std::move(s));
    } else {
      signals.push_back(environmentSignal(input, kind));
    }
  }
  std::string positions;
  for (const std::string& s : skipped) positions += (positions.empty() ? "" : "; ") + s;
  if (signals.empty())
    throw InputError(fmt::format("no scene suggests a partly occluded probe position (open between {} and {} of the "
                                 "sphere): nothing to evaluate on; left out: {}",
                                 kMinOpenFraction, 1.0 - kMinOpenFraction, positions));
  return signals;
}

int printEvaluation(SignalKind kind, SignalMetric metric, const std::vector<std::string>& inputs,
                    std::vector<std::string> names, bool json) {
  if (names.empty()) names = basisNames();
  std::vector<std::string> unique;
  for (const std::string& name : names) {
    // An unknown name is refused before any work; so is a basis that holds one hemisphere, which
    // these whole-sphere scores would misjudge (`baker env --signal radiance` reads it).
    if (makeBasis(name)->hemisphere())
      throw InputError(fmt::format("--basis {}: holds radiance over one hemisphere only; score it with baker env "
                                   "--signal radiance, which reads it at the surfaces it serves",
                                   name));
    if (std::find(unique.begin(), unique.end(), name) == unique.end()) unique.push_back(name);
  }
  names = unique;
  std::vector<std::string> skipped;
  const std::vector<SphereSignal> signals = loadSignals(kind, inputs, skipped);
  for (const std::string& s : skipped)
    std::cerr << fmt::format("baker bases: left out {}: not partly occluded\n", s);
  const std::vector<BasisScore> scores = evaluateBases(names, signals, metric);
  if (json) {
    nlohmann::json rows = nlohmann::json::array(), signalNames = nlohmann::json::array();
    for (const SphereSignal& s : signals) signalNames.push_back(s.name);
    for (const BasisScore& score : scores)
      rows.push_back({{"basis", score.basis},
                      {"fit", fitMethodName(score.fit)},
                      {"bytes_per_probe", score.bytesPerProbe},
                      {"mean", score.mean},
                      {"standard_deviation", score.standardDeviation},
                      {"per_signal", score.perSignal}});
    const nlohmann::json out = {{"signal", signalKindName(kind)},
                                {"metric", signalMetricName(metric)},
                                {"higher_is_better", higherIsBetter(metric)},
                                {"signal_width", kSignalWidth},
                                {"signal_height", kSignalWidth / 2},
                                {"signals", signalNames},
                                {"left_out", skipped},
                                {"scores", rows}};
    std::cout << out.dump(2) << "\n";
    return 0;
  }
  std::cout << fmt::format("{} of {} signal(s), {} ({} is better); bytes per probe at 32-bit floats\n\n",
                           signalMetricName(metric), signals.size(), signalKindName(kind),
                           higherIsBetter(metric) ? "higher" : "lower");
  std::cout << fmt::format("{:<14} {:<13} {:>6} {:>10} {:>10}\n", "basis", "fit", "bytes", "mean", "std dev");
  for (const BasisScore& score : scores)
    std::cout << fmt::format("{:<14} {:<13} {:>6} {:>10.4g} {:>10.4g}\n", score.basis, fitMethodName(score.fit),
                             score.bytesPerProbe, score.mean, score.standardDeviation);
  return 0;
}

}  // namespace

int runBasesCommand(int argc, char** argv) {
  CLI::App app{
      "List every basis with its coefficient counts and SH reproduction norms (paper eq. 9); with --signal, "
      "evaluate every basis on test signals as Nielsen's thesis does (docs/BASES.md)."};
  bool json = false;
  std::string signal, metric = "rmae";
  std::vector<std::string> inputs, names;
  app.add_flag("--json", json, "print as JSON on stdout");
  app.add_option("--signal", signal,
                 "evaluate on this signal: radiance or irradiance (of the lat-long light probes given), occlusion (at "
                 "the probe positions the glTF scenes given suggest)");
  app.add_option("--metric", metric, "rmae (default), rmse or ssim");
  app.add_option("--basis", names, "evaluate only these bases (repeatable; default: every one)")
      ->allow_extra_args(false);
  app.add_option("inputs", inputs, "with --signal: lat-long HDR or EXR images, or for occlusion glTF scenes");
  return runGuarded("baker bases", app, argc, argv, [&]() {
    if (!app.count("--signal")) {
      if (!inputs.empty() || app.count("--metric") || !names.empty())
        throw InputError("inputs, --metric and --basis need --signal radiance|irradiance|occlusion");
      return printListing(json);
    }
    const SignalKind kind = parseSignalKind(signal);
    const SignalMetric parsedMetric = parseSignalMetric(metric);
    if (inputs.empty())
      throw SettingError("signal", kind == SignalKind::Occlusion
                                       ? "occlusion needs glTF scenes that suggest probe positions"
                                       : fmt::format("{} needs lat-long light probes (HDR or EXR)", signal));
    return printEvaluation(kind, parsedMetric, inputs, names, json);
  });
}

}  // namespace baker
