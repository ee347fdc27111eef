#pragma once
#include <string>
#include <vector>

#include "validate/SignalFit.h"
#include "validate/SignalMetrics.h"
#include "validate/SphereSignals.h"

namespace baker {

// One basis with one fit, scored on every signal: `baker bases --signal … --metric …`.
struct BasisScore {
  std::string basis;
  FitMethod fit = FitMethod::Linear;
  int bytesPerProbe = 0;             // at 32-bit floats (FittedSignal::bytesPerProbe)
  std::vector<double> perSignal;     // in the signals' order
  double mean = 0.0;
  double standardDeviation = 0.0;    // over signals, with n − 1 (0 for one signal)
};

// Every basis of `basisNames` with every fit that applies to it (linear, then non-negative), in
// that order, on every signal. The same numbers on any thread count. std::invalid_argument when
// there is no signal.
std::vector<BasisScore> evaluateBases(const std::vector<std::string>& basisNames, const std::vector<SphereSignal>& signals,
                                      SignalMetric metric);

}  // namespace baker
