#include "cli/AccuracyCommand.h"

#include <fmt/format.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "cli/BakeOptions.h"
#include "cli/CommandLine.h"
#include "common/Error.h"
#include "formats/AtomicFile.h"
#include "validate/AccuracyStudy.h"

namespace baker {
namespace {

std::vector<int> parseIntList(const std::string& flag, const std::string& text) {
  std::vector<int> values;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    try {
      std::size_t used = 0;
      values.push_back(std::stoi(item, &used));
      if (used != item.size()) throw std::invalid_argument(item);
    } catch (const std::logic_error&) {
      throw InputError(fmt::format("{} {}: \"{}\" is not an integer", flag, text, item));
    }
  }
  return values;
}

std::vector<std::string> parseNameList(const std::string& text) {
  std::vector<std::string> names;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ','))
    if (!item.empty()) names.push_back(item);
  return names;
}

}  // namespace

int runAccuracyCommand(int argc, char** argv) {
  CLI::App app{"Measure what accuracy costs: bake every basis × rays × bounces combination and compare with a "
               "converged reference."};
  BakeOptions options;
  std::string basisList = "sh-l2,ad-srbf,ad-ycocg", raysList = "64,256,1024", bouncesList = "3", outDir = "accuracy";
  AccuracyPlan plan;
  addBakeOptions(app, options, true);
  app.add_option("--basis", basisList, "comma-separated bases")->capture_default_str();
  app.add_option("--rays", raysList, "comma-separated ray counts per probe")->capture_default_str();
  app.add_option("--bounces", bouncesList, "comma-separated bounce counts")->capture_default_str();
  app.add_option("--out", outDir, "directory for accuracy.csv, accuracy.json, accuracy.svg, accuracy.md")
      ->capture_default_str();
  app.add_option("--reference-rays", plan.referenceRays, "rays of the reference; default: 16 × the largest --rays");
  app.add_option("--probes", plan.measuredProbes, "probes the error is measured at")->capture_default_str();
  return runGuarded("baker accuracy", app, argc, argv, [&]() {
    plan.bases = parseNameList(basisList);
    plan.rays = parseIntList("--rays", raysList);
    plan.bounces = parseIntList("--bounces", bouncesList);
    validateAccuracyPlan(plan);
    options.request.bounces = *std::max_element(plan.bounces.begin(), plan.bounces.end());
    // The job's own basis is the first listed, so that --sg-sharpness and --non-negative are
    // checked against a basis of the study.
    options.request.basis = plan.bases.front();
    std::filesystem::create_directories(outDir);
    const std::unique_ptr<BakeJob> job = prepareBake(app, options, std::cerr);
    const AccuracyStudy study = measureAccuracy(*job, plan, [](const AccuracyRow& r) {
      std::cerr << fmt::format("{:<12} {:>7} rays {:>2} bounces: {:8.3f} s, relative RMSE {:.4g}\n", r.basis, r.rays,
                               r.bounces, r.bakeSeconds, r.relativeRmse);
    });
    for (const auto& [file, text] : accuracyReports(study)) {
      AtomicFile out((std::filesystem::path(outDir) / file).string());
      std::ofstream(out.temporaryPath()) << text;
      out.commit();
      if (file == "accuracy.md") std::cout << text;
    }
    return 0;
  });
}

}  // namespace baker
