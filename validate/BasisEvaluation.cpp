#include "validate/BasisEvaluation.h"

#include <tbb/parallel_for.h>

#include <cmath>
#include <memory>
#include <stdexcept>

#include "basis/BasisRegistry.h"

namespace baker {
namespace {

void summarise(BasisScore& score) {
  const double n = double(score.perSignal.size());
  double sum = 0.0;
  for (const double v : score.perSignal) sum += v;
  score.mean = sum / n;
  double squares = 0.0;
  for (const double v : score.perSignal) squares += (v - score.mean) * (v - score.mean);
  score.standardDeviation = n > 1 ? std::sqrt(squares / (n - 1)) : 0.0;
}

}  // namespace

std::vector<BasisScore> evaluateBases(const std::vector<std::string>& basisNames, const std::vector<SphereSignal>& signals,
                                      SignalMetric metric) {
  if (signals.empty()) throw std::invalid_argument("evaluateBases: no signal to evaluate on");
  std::vector<std::shared_ptr<Basis>> bases;
  std::vector<BasisScore> scores;
  for (const std::string& name : basisNames) {
    bases.push_back(makeBasis(name));
    for (const FitMethod fit : {FitMethod::Linear, FitMethod::NonNegative})
      if (fitApplies(*bases.back(), fit)) scores.push_back({name, fit, 0, std::vector<double>(signals.size()), 0.0, 0.0});
  }
  // Each (score, signal) pair is computed on its own and written to its own slot.
  tbb::parallel_for(std::size_t(0), scores.size() * signals.size(), [&](std::size_t job) {
    BasisScore& score = scores[job / signals.size()];
    const SphereSignal& signal = signals[job % signals.size()];
    std::size_t b = 0;
    while (basisNames[b] != score.basis) ++b;
    const FittedSignal fitted(*bases[b], signal, score.fit);
    score.perSignal[job % signals.size()] = signalScore(signal, fitted, metric);
    if (job % signals.size() == 0) score.bytesPerProbe = fitted.bytesPerProbe();
  });
  for (BasisScore& score : scores) summarise(score);
  return scores;
}

}  // namespace baker
