#include "cli/BasesCommand.h"

#include <fmt/format.h>

#include <iostream>
#include <nlohmann/json.hpp>

#include "basis/BasisRegistry.h"
#include "basis/GramOperators.h"
#include "cli/CommandLine.h"

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

}  // namespace

int runBasesCommand(int argc, char** argv) {
  CLI::App app{"List every basis with its coefficient counts and SH reproduction norms (paper eq. 9)."};
  bool json = false;
  app.add_flag("--json", json, "print as JSON on stdout");
  return runGuarded("baker bases", app, argc, argv, [&]() {
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
  });
}

}  // namespace baker
