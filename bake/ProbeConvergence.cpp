#include "bake/ProbeConvergence.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace baker {

std::int64_t raysAfterRounds(int rays, int rounds) {
  return 2 * std::int64_t(rays) * ((std::int64_t(1) << rounds) - 1);
}

const std::vector<QualityPreset>& qualityPresets() {
  // Rounds of two lattices of 256·2^t. The targets and limits are chosen on the reference scenes
  // (docs/SAMPLING.md): "default" keeps one bake of every one of them within 5 % of Cycles on
  // every probe, axis and channel. Rays after 1…10 rounds: 512, 1536, 3584, 7680, 15872, 32256,
  // 65024, 130560, 261632, 523776.
  static const std::vector<QualityPreset> presets = {
      {"draft", 256, {0.05, 1, 4}},
      {"default", 256, {0.01, 2, 9}},
      {"final", 256, {0.005, 3, 11}},
  };
  return presets;
}

const QualityPreset* findQualityPreset(const std::string& name) {
  for (const QualityPreset& p : qualityPresets())
    if (name == p.name) return &p;
  return nullptr;
}

std::string qualityPresetNames() {
  std::string names;
  for (const QualityPreset& p : qualityPresets()) names += (names.empty() ? "" : ", ") + std::string(p.name);
  return names;
}

void RoundStatistics::add(int rays, const AxisIrradiance& first, const AxisIrradiance& second) {
  previousError_ = relativeStandardError();
  const double n = rays;
  weighted_ += n * (first + second);
  spread_ += (n * n) * (first - second).cwiseAbs2();
  rays_ += 2 * std::int64_t(rays);
  ++rounds_;
}

double RoundStatistics::relativeStandardError() const {
  if (rounds_ == 0) return std::numeric_limits<double>::infinity();
  // The round means m_t = (a + b)/2 enter the mean with weight 2n_t/N, and Var(m_t) is
  // estimated without bias by (a − b)²/4: Var(mean) = Σ n_t² (a − b)² / N².
  const double total = double(rays_);
  const AxisIrradiance magnitude = (mean() + fixed_).cwiseAbs();
  double worst = 0.0;
  for (int c = 0; c < 3; ++c) {
    const double halfMean = 0.5 * magnitude.col(c).mean();
    for (int a = 0; a < 6; ++a) {
      const double standardError = std::sqrt(spread_(a, c)) / total;
      if (!(standardError > 0.0)) continue;  // no noise (a black channel): nothing to wait for
      const double scale = magnitude(a, c) + halfMean;
      worst = std::max(worst, standardError / scale);
    }
  }
  return worst;
}

bool RoundStatistics::converged(const ConvergenceSettings& settings) const {
  // Two rounds in a row: one round's estimate of the error rests on few differences, and a probe
  // whose two lattices happen to agree would otherwise stop early.
  return rounds_ >= settings.minRounds && relativeStandardError() <= settings.targetError &&
         previousError_ <= settings.targetError;
}

void RoundTally::add(std::int64_t probeRays, bool reachedLimit) {
  ++probes;
  rays += probeRays;
  mostRays = std::max(mostRays, probeRays);
  atLimit += reachedLimit;
}

RoundTally& RoundTally::operator+=(const RoundTally& other) {
  probes += other.probes;
  rays += other.rays;
  mostRays = std::max(mostRays, other.mostRays);
  atLimit += other.atLimit;
  return *this;
}

}  // namespace baker
