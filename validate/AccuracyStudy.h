#pragma once
#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "bake/BakeJob.h"

namespace baker {

// What `baker accuracy` measures: every basis × ray count × bounce count baked over the job's
// grid, against a converged reference at `measuredProbes` probes spread over it.
struct AccuracyPlan {
  std::vector<std::string> bases;
  std::vector<int> rays;
  std::vector<int> bounces;
  int referenceRays = 0;  // 0: 16 × the largest ray count, at most kMaxRaysPerProbe
  int measuredProbes = 64;
};

struct AccuracyRow {
  std::string basis;
  int rays = 0, bounces = 0;
  double bakeSeconds = 0.0, operatorSeconds = 0.0, traceSeconds = 0.0;
  double relativeRmse = 0.0, maxRelativeError = 0.0;
};

struct AccuracyStudy {
  std::string sceneName;
  ProbeGrid grid;
  int referenceRays = 0;
  std::size_t measuredProbes = 0, normals = 0;
  int threads = 0;
  std::vector<AccuracyRow> rows;
};

// SettingError naming "basis", "rays", "bounces", "reference_rays" or "probes" for a bad plan.
void validateAccuracyPlan(const AccuracyPlan& plan);

// Runs the plan on the job's scene and grid; `onRow` hears each row as it is measured.
AccuracyStudy measureAccuracy(const BakeJob& job, AccuracyPlan plan, const std::function<void(const AccuracyRow&)>& onRow);

// accuracy.csv, accuracy.json, accuracy.svg and accuracy.md: file name and contents.
std::vector<std::pair<std::string, std::string>> accuracyReports(const AccuracyStudy& study);

}  // namespace baker
