#pragma once
#include <Eigen/Core>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace baker {

// How long a probe keeps tracing. With maxRounds = 0 a probe traces one lattice of `rays`
// directions (BakeSettings). Otherwise it traces rounds: round t is two independent lattices of
// rays·2^t directions each, every lattice in a random rotation of its own with random numbers of
// its own, so that the rays traced double every round. After each round the probe's irradiance
// on the six axes is the mean over all its rays, and its standard error follows from the
// difference between each round's two lattices. The probe stops once that error is at most
// targetError × S on every axis and channel, S = |E| + ½ · (the channel's mean E over the axes),
// the scale the Cycles references are judged on (docs/SAMPLING.md), after two rounds in a row;
// after at least minRounds and at most maxRounds rounds.
//
// Why lattices that double, not many small ones: a lattice is stratified, and for what a probe
// sees (edges of lit patches, shadows) its variance falls faster than 1/N; independent small
// lattices would lose that and need several times the rays. Why two per round: the difference
// of two independent estimates is an honest measure of the noise from every source (aliasing,
// bounces, MIS), where a variance over the rays of one lattice is not.
struct ConvergenceSettings {
  double targetError = 0.0;
  int minRounds = 1;
  int maxRounds = 0;
  bool adaptive() const { return maxRounds > 0; }
};

// The directions a probe has traced after `rounds` rounds of lattices of rays·2^t.
std::int64_t raysAfterRounds(int rays, int rounds);

// The presets of `--quality`, in increasing cost; docs/SAMPLING.md gives each one's time and
// error on the reference scenes (scripts/quality_report.sh).
struct QualityPreset {
  const char* name;
  int rays;  // of round 0's lattices
  ConvergenceSettings convergence;
};
const std::vector<QualityPreset>& qualityPresets();
// The preset called `name`, or null.
const QualityPreset* findQualityPreset(const std::string& name);
// "draft, default, final": for help texts and messages.
std::string qualityPresetNames();

// A probe's rounds: the mean of its axis irradiances over all rays and its standard error.
class RoundStatistics {
 public:
  using AxisIrradiance = Eigen::Matrix<double, 6, 3>;  // rows +X −X +Y −Y +Z −Z, columns R G B

  // `fixed`: the part of the probe's irradiance that has no noise (punctual lights seen
  // directly), counted in the scale S but not in the error.
  explicit RoundStatistics(const AxisIrradiance& fixed) : fixed_(fixed) {}

  // One round: two independent estimates from lattices of `rays` directions each.
  void add(int rays, const AxisIrradiance& first, const AxisIrradiance& second);
  int rounds() const { return rounds_; }
  AxisIrradiance mean() const { return weighted_ / double(rays_); }
  // max over axes and channels of (standard error of the mean) / S; infinite before a round.
  double relativeStandardError() const;
  bool converged(const ConvergenceSettings& settings) const;

 private:
  AxisIrradiance fixed_;
  AxisIrradiance weighted_ = AxisIrradiance::Zero();  // Σ n_t (first + second)
  AxisIrradiance spread_ = AxisIrradiance::Zero();    // Σ n_t² (first − second)²
  std::int64_t rays_ = 0;
  int rounds_ = 0;
  double previousError_ = std::numeric_limits<double>::infinity();  // before the last round
};

// What the rounds of a batch of probes came to, for the bake's report.
struct RoundTally {
  std::int64_t probes = 0;
  std::int64_t rays = 0;          // lattice directions, summed over probes
  std::int64_t mostRays = 0;      // of any one probe
  std::int64_t atLimit = 0;       // probes that stopped at maxRounds short of the target
  void add(std::int64_t probeRays, bool reachedLimit);
  RoundTally& operator+=(const RoundTally& other);
};

}  // namespace baker
