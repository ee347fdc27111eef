#include "bake/ProbeBaker.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <mutex>
#include <numeric>
#include <optional>
#include <stdexcept>

#include "bake/PathRandom.h"
#include "bake/ScratchBuffer.h"
#include "basis/DirectionSet.h"
#include "basis/NonNegativeProjection.h"
#include "basis/ProjectionOperator.h"
#include "basis/SphericalHarmonics.h"
#include "common/Error.h"

namespace baker {
namespace {

// Probes traced per task: about a millisecond of work at 256 rays, far above the cost of a task.
constexpr int kProbesPerTask = 8;

// A uniformly random rotation (Shoemake's method).
Eigen::Matrix3f randomRotation(PathRandom random) {
  const double u1 = random.uniform(), u2 = 2.0 * M_PI * random.uniform(), u3 = 2.0 * M_PI * random.uniform();
  const double a = std::sqrt(1.0 - u1), b = std::sqrt(u1);
  const Eigen::Quaterniond q(b * std::cos(u3), a * std::sin(u2), a * std::cos(u2), b * std::sin(u3));
  return q.normalized().toRotationMatrix().cast<float>();
}

// The bake's lattice rotations, drawn from the seed: the same for a seed in every bake,
// independent from seed to seed.
Eigen::Matrix3f seededRotation(std::uint64_t seed, int index) {
  return randomRotation(PathRandom(0x726f746174696f6eull ^ seed, std::uint64_t(index), 0));
}

// The rotation of a probe's lattice under adaptive convergence, the probe's own: the lattices of
// neighbouring probes never line up.
Eigen::Matrix3f latticeRotation(std::uint64_t seed, std::uint64_t probeId, int lattice) {
  return randomRotation(PathRandom(0x6c61747469636573ull ^ seed, probeId, std::uint64_t(lattice)));
}

// The id a probe's lattice draws its random numbers with (PathIntegrator, DirectView): probe
// ids stay below 2^40.
std::uint64_t latticeProbeId(std::uint64_t probeId, int lattice) {
  return probeId ^ (std::uint64_t(lattice) << 40);
}

const Eigen::Vector3f kAxes[6] = {Eigen::Vector3f::UnitX(),  -Eigen::Vector3f::UnitX(), Eigen::Vector3f::UnitY(),
                                  -Eigen::Vector3f::UnitY(), Eigen::Vector3f::UnitZ(),  -Eigen::Vector3f::UnitZ()};

void addAxisIrradiance(const std::vector<PunctualAtProbe::Arrival>& arrivals, RoundStatistics::AxisIrradiance* e) {
  for (const PunctualAtProbe::Arrival& a : arrivals)
    for (int n = 0; n < 6; ++n)
      e->row(n) += a.irradiance.cast<double>().transpose() * double(std::max(0.0f, kAxes[n].dot(a.direction)));
}

// The six axis irradiances one lattice and its direct-view samples imply, RGB.
RoundStatistics::AxisIrradiance latticeIrradiance(const Eigen::Vector3f* directions, const std::vector<double>& weights,
                                                  const Eigen::Vector3f* radiance,
                                                  const std::vector<PunctualAtProbe::Arrival>& direct) {
  RoundStatistics::AxisIrradiance e = RoundStatistics::AxisIrradiance::Zero();
  for (std::size_t r = 0; r < weights.size(); ++r)
    for (int n = 0; n < 6; ++n)
      e.row(n) += radiance[r].cast<double>().transpose() *
                  (weights[r] * double(std::max(0.0f, kAxes[n].dot(directions[r]))));
  addAxisIrradiance(direct, &e);
  return e;
}

// The order punctual deltas are expanded to: the highest any of the basis's function sets needs.
int punctualShOrder(const Basis& basis) {
  int order = 0;
  for (int c = 0; c < 3; ++c) order = std::max(order, PunctualAtProbe::shOrderFor(basis.functions(c)));
  return order;
}

DirectionSet rotated(const DirectionSet& set, const Eigen::Matrix3f& rotation) {
  DirectionSet out = set;
  for (Eigen::Vector3d& d : out.directions) d = (rotation.cast<double>() * d).normalized();
  return out;
}

}  // namespace

Eigen::Vector3f sampledIrradiance(const ProbeSamples& s, const Eigen::Vector3f& n) {
  Eigen::Vector3d e = Eigen::Vector3d::Zero();
  for (std::size_t r = 0; r < s.radiance.size(); ++r)
    e += s.radiance[r].cast<double>() * (s.weights[r] * std::max(0.0f, n.dot(s.directions[r])));
  for (const auto* arrivals : {&s.punctual, &s.direct})
    for (const PunctualAtProbe::Arrival& a : *arrivals)
      e += a.irradiance.cast<double>() * double(std::max(0.0f, n.dot(a.direction)));
  return e.cast<float>();
}

SampledSpecular sampledSpecular(const ProbeSamples& s, const GgxLobe& lobe) {
  SampledSpecular result;
  const double albedo = result.albedo = lobe.albedo();
  Eigen::Vector3d rays = Eigen::Vector3d::Zero(), deltas = Eigen::Vector3d::Zero();
  double covered = 0.0;
  for (std::size_t r = 0; r < s.radiance.size(); ++r) {
    const double weight = s.weights[r] * lobe.cosineWeighted(s.directions[r].cast<double>());
    rays += s.radiance[r].cast<double>() * weight;
    covered += weight;
  }
  for (const auto* arrivals : {&s.punctual, &s.direct})
    for (const PunctualAtProbe::Arrival& a : *arrivals)
      deltas += a.irradiance.cast<double>() * lobe.cosineWeighted(a.direction.cast<double>());
  result.rayCoverage = covered / albedo;
  // The rays' share over their own sum of weights, so that their quadrature error cancels where
  // the radiance is smooth; the deltas' share is exact.
  const Eigen::Vector3d fromRays = covered > 0.0 ? Eigen::Vector3d(rays / covered) : Eigen::Vector3d::Zero();
  result.value = (fromRays + deltas / albedo).cast<float>();
  return result;
}

// Consecutive colour channels that share one function set are projected together: for an RGB
// basis that is one product over all three channels.
struct ProbeBaker::ChannelGroup {
  int firstChannel = 0;
  int channelCount = 0;
  int functions = 0;
  // Per rotation: functions × rays, samples → coefficients. Row-major, so that each coefficient
  // is one contiguous dot product with a probe's contiguous samples.
  std::vector<Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> fromSamples;
  // functions × the punctual expansion's count: lights → coefficients.
  Eigen::MatrixXd fromPunctual;
  // functions × the direct expansion's count: direct-view samples (and adaptive lattices) →
  // coefficients; for irradiance the lattice's own SH→irradiance operator, so that the samples
  // and the lattice's share of the same light are projected alike.
  Eigen::MatrixXd fromDirect;
  Eigen::MatrixXd gram;                      // G: for the non-negative solve and the radiance rounds
};

ProbeBaker::ProbeBaker(const Scene& scene, const RayTracer& tracer, const Basis& basis, const BakeSettings& settings,
                       int rotations)
    : basis_(basis),
      settings_(settings),
      integrator_(scene, tracer, settings.transport),
      punctual_(scene, tracer, punctualShOrder(basis)),
      directView_(scene, tracer, settings.transport, integrator_.emitters(), integrator_.lightAim()),
      coefficientsPerProbe_(basis.totalCoefficients()),
      visibilityPerProbe_(basis.functions(0).count()),
      keepsSkyDirect_(settings.transport.environment && scene.environment.emits() && !settings.projection.nonNegative),
      keepsSkyBounced_(keepsSkyDirect_ && settings.transport.bounces > 0) {
  const DirectionSet fibonacci = sphericalFibonacci(settings.rays);
  weights_ = fibonacci.weights;
  for (int round = 0; round < settings.convergence.maxRounds; ++round)
    roundLattices_.push_back(sphericalFibonacci(settings.rays << round));
  shOrder_ = std::min(resolvableShOrder(fibonacci.size()), kMaxSampleShOrder);
  directHarmonics_ = SphericalHarmonics(shOrder_);
  std::vector<DirectionSet> sets;
  for (int r = 0; r < rotations; ++r) {
    sets.push_back(rotated(fibonacci, seededRotation(settings.transport.seed, r)));
    std::vector<Eigen::Vector3f> d;
    for (const Eigen::Vector3d& v : sets.back().directions) d.push_back(v.cast<float>());
    directions_.push_back(std::move(d));
  }
  if (settings.distanceMapSize > 0 && !settings.convergence.adaptive() && settings.rays <= kMostRaysWithDistanceWeights)
    for (const std::vector<Eigen::Vector3f>& d : directions_)
      distanceWeights_.emplace_back(DistanceMapLayout::baked(settings.distanceMapSize, 0.0), d.data(), int(d.size()));
  for (int c = 0; c < 3; ++c) {
    if (c > 0 && &basis.functions(c) == &basis.functions(c - 1)) {
      ++groups_.back().channelCount;
      continue;
    }
    ChannelGroup group;
    group.firstChannel = c;
    group.channelCount = 1;
    group.functions = basis.functions(c).count();
    groups_.push_back(std::move(group));
  }
  if (settings.projection.signal == StoredSignal::Radiance)
    buildRadianceOperators(sets);
  else
    buildIrradianceOperators(sets);
}

void ProbeBaker::buildIrradianceOperators(const std::vector<DirectionSet>& sets) {
  punctualExpansion_ = &punctual_.harmonics();
  directExpansion_ = &directHarmonics_;
  // Each rotation's SH fit of the samples serves every function set of the basis. Only the
  // first rotation's conditioning is computed: the others have the same spectrum.
  const SphericalHarmonics sampleSh(shOrder_);
  std::vector<SampledFit> shFits;
  for (std::size_t r = 0; r < sets.size(); ++r)
    shFits.emplace_back(sampleSh, sets[r], basis_.name() + " (SH fit of the samples)",
                        r == 0 ? SampledFit::Conditioning::Check : SampledFit::Conditioning::CheckedByRotation);
  const bool punctualAtProbe = settings_.transport.directPunctual && !punctual_.empty();
  for (ChannelGroup& group : groups_) {
    const GramOperators ops(basis_.functions(group.firstChannel), basis_.name());
    condition_ = std::max(condition_, ops.conditionNumber());
    // G⁻¹ B_sh C after each rotation's fit P: samples → irradiance coefficients in one operator.
    const Eigen::MatrixXd fromSh = ops.irradianceFromSh(shOrder_, settings_.projection.window);
    for (const SampledFit& fit : shFits) group.fromSamples.push_back(fit.after(fromSh).cast<float>());
    if (punctualAtProbe) group.fromPunctual = ops.irradianceFromSh(punctual_.shOrder(), settings_.projection.window);
    if (!directView_.empty() || settings_.convergence.adaptive()) group.fromDirect = fromSh;
    if (settings_.projection.nonNegative) group.gram = ops.gram();
  }
  // Deltas are expanded only up to the last SH band an operator reads: a basis of low degree
  // takes nothing from higher bands (sh-l2 reads bands 0-2 of the lattice's 0-15 at 1024 rays),
  // their columns are exact zeros, and evaluating and summing them took a fifth of a bake.
  if (punctualAtProbe) {
    punctualHarmonics_ = SphericalHarmonics(lastBandRead(&ChannelGroup::fromPunctual, punctual_.shOrder()));
    punctualExpansion_ = &punctualHarmonics_;
    for (ChannelGroup& group : groups_) group.fromPunctual = group.fromPunctual.leftCols(punctualHarmonics_.count()).eval();
  }
  if (groups_.front().fromDirect.size()) {
    directHarmonics_ = SphericalHarmonics(lastBandRead(&ChannelGroup::fromDirect, shOrder_));
    for (ChannelGroup& group : groups_) group.fromDirect = group.fromDirect.leftCols(directHarmonics_.count()).eval();
  }
}

int ProbeBaker::lastBandRead(const Eigen::MatrixXd ChannelGroup::*shOperator, int order) const {
  for (int band = order; band > 0; band -= 1)  // (not "--band": a flag, to scripts/check_layers.py)
    for (const ChannelGroup& group : groups_)
      if (!(group.*shOperator).middleCols(band * band, 2 * band + 1).isZero(0.0)) return band;
  return 0;
}

// The rounds' moments m become c = (BᵀWB)⁻¹m, the least-squares fit of the probe's own rays that
// the fixed lattice makes, so that a constant sky is held exactly here too (the moments alone
// would carry their quadrature's error, 0.5 % for ad-srbf at 256 rays). They are handed on as
// the moments G·c, which projectLatticeExpansion's G⁻¹ turns back into c.
void ProbeBaker::fitRoundsByLeastSquares(const Eigen::MatrixXd& sampledGram, Eigen::MatrixXd& latticeExpansion,
                                         int taskIndex, int batchSize, int skyParts) const {
  for (std::size_t g = 0; g < groups_.size(); ++g) {
    const ChannelGroup& group = groups_[g];
    const int offset = ownFunctions_.offset(int(g)), n = group.functions;
    const Eigen::LDLT<Eigen::MatrixXd> fit(sampledGram.block(offset, offset, n, n));
    if (fit.info() != Eigen::Success || !(fit.rcond() > 1e-12))
      throw NumericalError(basis_.name() + ": a probe's rays do not resolve the basis's functions (radiance fit)");
    std::vector<int> columns;
    for (int c = 0; c < group.channelCount; ++c) columns.push_back(group.firstChannel + c);
    if (g == 0) columns.push_back(3);  // sky visibility, in channel 0's functions
    for (int part = 0; part < skyParts; ++part)  // the sky's channels, seen directly and off surfaces
      for (int c = 0; c < group.channelCount; ++c) columns.push_back(4 + 3 * part + group.firstChannel + c);
    for (int c : columns) {
      auto moments = latticeExpansion.block(offset, c * batchSize + taskIndex, n, 1);
      moments = group.gram * fit.solve(Eigen::VectorXd(moments));
    }
  }
}

void ProbeBaker::buildRadianceOperators(const std::vector<DirectionSet>& sets) {
  std::vector<const SphericalFunctions*> groupFunctions;
  for (const ChannelGroup& group : groups_) groupFunctions.push_back(&basis_.fitFunctions(group.firstChannel));
  ownFunctions_ = StackedFunctions(groupFunctions);
  punctualExpansion_ = &ownFunctions_;
  directExpansion_ = &ownFunctions_;
  for (std::size_t g = 0; g < groups_.size(); ++g) {
    ChannelGroup& group = groups_[g];
    const SphericalFunctions& fitted = basis_.fitFunctions(group.firstChannel);
    const GramOperators ops(fitted, basis_.name());
    condition_ = std::max(condition_, ops.conditionNumber());
    // Weighted least squares of each rotation's samples, which reproduces any radiance the
    // functions can hold (a constant sky, for most bases) exactly, where the quadrature's moments
    // G⁻¹BᵀW would carry its error. Lobes are not rotation-invariant: each rotation is checked.
    for (const DirectionSet& set : sets) {
      const SampledFit fit(fitted, set, basis_.name() + " (radiance fit of the samples)");
      condition_ = std::max(condition_, fit.conditionNumber());
      group.fromSamples.push_back(fit.matrix().cast<float>());
    }
    // Deltas' moments arrive in the stacked functions of every group: this group reads its own.
    Eigen::MatrixXd fromOwn = Eigen::MatrixXd::Zero(group.functions, ownFunctions_.count());
    fromOwn.middleCols(ownFunctions_.offset(int(g)), group.functions) = ops.gramInverse();
    group.fromPunctual = fromOwn;
    group.fromDirect = std::move(fromOwn);
    group.gram = ops.gram();
  }
}

namespace {

// A lattice's rays: directions, quadrature weights and what each brought back (radiance, whether
// it escaped, and the sky's light off surfaces when that is kept apart).
struct LatticeRays {
  const Eigen::Vector3f* directions;
  const std::vector<double>* weights;
  int count;
  const Eigen::Vector3f* radiance;
  const float* sky;
  const Eigen::Vector3f* bounced;
};

// The lattice as deltas, like the direct-view samples: n·w·L(ω)·f(ω) per ray, n its size, into
// the probe's columns of `expansion` (c·batchSize + taskIndex: channels 0-2, sky visibility 3,
// then each kept part of the sky's channels), and ray by ray into `sampledGram` (BᵀWB) when given.
void addRaysAsDeltas(const SphericalFunctions& functions, ColorSpace space, const LatticeRays& rays, int skyParts,
                     int taskIndex, int batchSize, Eigen::MatrixXd& expansion, Eigen::MatrixXd* sampledGram) {
  const int count = functions.count();
  thread_local std::vector<double> y;
  y.resize(std::size_t(count));
  const auto add = [&](int firstColumn, const Eigen::Vector3d& value) {
    for (int i = 0; i < count; ++i)
      for (int c = 0; c < 3; ++c) expansion(i, (firstColumn + c) * batchSize + taskIndex) += value[c] * y[i];
  };
  for (int r = 0; r < rays.count; ++r) {
    const double weight = (*rays.weights)[std::size_t(r)] * rays.count;
    functions.evaluate(rays.directions[r].cast<double>(), y.data());
    const Eigen::Vector3d value = toColorSpace(space, rays.radiance[r]).cast<double>() * weight;
    add(0, value);
    const double seen = double(rays.sky[r]) * weight;
    for (int i = 0; i < count; ++i) expansion(i, 3 * batchSize + taskIndex) += seen * y[i];
    // An escaped ray brought back the sky alone (PathIntegrator): its value is the sky's.
    if (skyParts > 0 && rays.sky[r] > 0.0f) add(4, value);
    if (skyParts > 1) add(7, toColorSpace(space, rays.bounced[r]).cast<double>() * weight);
    if (sampledGram)
      sampledGram->selfadjointView<Eigen::Lower>().rankUpdate(Eigen::Map<const Eigen::VectorXd>(y.data(), count),
                                                              weight);
  }
}

}  // namespace

ProbeBaker::~ProbeBaker() = default;

ProbeBaker::Rounds ProbeBaker::traceRounds(const ProbeTask& task, const std::vector<PunctualAtProbe::Arrival>& lights,
                                           std::vector<PunctualAtProbe::Arrival>* direct, Eigen::MatrixXd& latticeExpansion,
                                           int taskIndex, int batchSize, int skyParts, RayCounts* counts,
                                           ProbeSamples* samples, DistanceMomentsAccumulator* distances) const {
  const ConvergenceSettings& convergence = settings_.convergence;
  const ColorSpace space = basis_.colorSpace();
  RoundStatistics::AxisIrradiance punctualPart = RoundStatistics::AxisIrradiance::Zero();
  addAxisIrradiance(lights, &punctualPart);
  RoundStatistics statistics(punctualPart);

  thread_local std::vector<Eigen::Vector3f> directions, radiance, bounced;
  thread_local std::vector<float> sky, hitDistance;
  thread_local std::vector<PunctualAtProbe::Arrival> latticeDirect;
  const SphericalFunctions& expansion = *directExpansion_;
  const int count = expansion.count();
  const bool fitsRadiance = settings_.projection.signal == StoredSignal::Radiance;
  thread_local Eigen::MatrixXd sampledGram;  // BᵀWB over the probe's lattices, lower triangle
  if (fitsRadiance) sampledGram.setZero(count, count);
  // Sums are of n·(the lattice's estimate), n its size: divided by all the rays at the end, each
  // ray weighs the same.
  direct->clear();
  while (statistics.rounds() < convergence.maxRounds && !statistics.converged(convergence)) {
    const int round = statistics.rounds();
    const DirectionSet& unturned = roundLattices_[round];
    const int rays = int(unturned.size());
    directions.resize(rays);
    radiance.resize(rays);
    bounced.resize(rays);
    sky.resize(rays);
    hitDistance.resize(rays);
    const ProbeView view = directView_.at(task.position, rays);
    RoundStatistics::AxisIrradiance estimates[2];
    for (int half = 0; half < 2; ++half) {
      const int lattice = 2 * round + half;
      const std::uint64_t id = latticeProbeId(task.id, lattice);
      const Eigen::Matrix3d turn = latticeRotation(settings_.transport.seed, task.id, lattice).cast<double>();
      for (int r = 0; r < rays; ++r) directions[r] = (turn * unturned.directions[r]).normalized().cast<float>();
      integrator_.trace(task.position, id, directions.data(), rays, radiance.data(), sky.data(), counts, &view,
                        distances ? hitDistance.data() : nullptr, skyParts > 1 ? bounced.data() : nullptr);
      // Every ray of every round weighs the same, as in the sums below.
      if (distances) distances->add(directions.data(), hitDistance.data(), rays);
      latticeDirect.clear();
      if (!directView_.empty()) directView_.sample(view, id, &latticeDirect, counts);
      estimates[half] = latticeIrradiance(directions.data(), unturned.weights, radiance.data(), latticeDirect);
      for (PunctualAtProbe::Arrival& a : latticeDirect) a.irradiance *= float(rays);
      direct->insert(direct->end(), latticeDirect.begin(), latticeDirect.end());
      addRaysAsDeltas(expansion, space, {directions.data(), &unturned.weights, rays, radiance.data(), sky.data(),
                                         skyParts > 1 ? bounced.data() : nullptr},
                      skyParts, taskIndex, batchSize, latticeExpansion, fitsRadiance ? &sampledGram : nullptr);
      if (samples) {
        samples->directions.insert(samples->directions.end(), directions.begin(), directions.end());
        for (double w : unturned.weights) samples->weights.push_back(w * rays);
        samples->radiance.insert(samples->radiance.end(), radiance.begin(), radiance.end());
        samples->visibility.insert(samples->visibility.end(), sky.begin(), sky.end());
      }
    }
    statistics.add(rays, estimates[0], estimates[1]);
  }
  const std::int64_t traced = raysAfterRounds(settings_.rays, statistics.rounds());
  for (int c = 0; c < 4 + 3 * skyParts; ++c) latticeExpansion.col(c * batchSize + taskIndex) /= double(traced);
  if (fitsRadiance) fitRoundsByLeastSquares(sampledGram / double(traced), latticeExpansion, taskIndex, batchSize, skyParts);
  for (PunctualAtProbe::Arrival& a : *direct) a.irradiance /= float(traced);
  if (samples)
    for (double& w : samples->weights) w /= double(traced);
  return {traced, statistics.converged(convergence)};
}

// Arrivals, per probe and channel in the colour space, expanded in a function set: for
// irradiance SH of the punctual lights and of the direct-view samples (up to the last band the
// operators read); for radiance the basis's own moments.
struct ProbeBaker::ArrivalExpansion {
  ArrivalExpansion(const SphericalFunctions& f, int probes) : functions(&f) { values.setZero(f.count(), 3 * probes); }
  const SphericalFunctions* functions;
  Eigen::MatrixXd values;  // count × 3p
  std::atomic<bool> any{false};

  void add(const std::vector<PunctualAtProbe::Arrival>& arrivals, int taskIndex, ColorSpace space) {
    if (arrivals.empty()) return;
    if (values.cols() == 0) throw std::logic_error("ProbeBaker: arrivals for an expansion sized for none");
    any = true;
    const int count = functions->count();
    const int probes = int(values.cols()) / 3;
    thread_local std::vector<double> rgb;
    rgb.assign(3 * std::size_t(count), 0.0);
    PunctualAtProbe::addExpansion(*functions, arrivals, rgb.data());
    for (int i = 0; i < count; ++i) {
      const Eigen::Vector3d arrival(rgb[i], rgb[count + i], rgb[2 * count + i]);
      const Eigen::Vector3d value = toColorSpace(space, arrival.cast<float>()).cast<double>();
      for (int c = 0; c < 3; ++c) values(i, c * probes + taskIndex) = value[c];
    }
  }
};

// Probes in order of rotation, so that each rotation's columns are one block: per rotation,
// channel 0 of its probes, then channel 1, channel 2, visibility, and for each part of the sky
// kept apart (seen directly; off surfaces) its channels 0, 1, 2 (`width` columns per probe). (A
// fixed lattice only.)
struct ProbeBaker::RotationBlocks {
  struct Block {
    int rotation, first, count;
  };
  std::vector<int> order;    // task indices in rotation order
  std::vector<Block> blocks;
  std::vector<int> blockOf;  // of each probe in rotation order
  int width;

  RotationBlocks(const std::vector<ProbeTask>& tasks, int skyParts)
      : order(tasks.size()), blockOf(tasks.size()), width(4 + 3 * skyParts) {
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return tasks[a].rotation < tasks[b].rotation; });
    for (std::size_t s = 0; s < tasks.size(); ++s) {
      const int rotation = tasks[order[s]].rotation;
      if (blocks.empty() || blocks.back().rotation != rotation) blocks.push_back({rotation, int(s), 0});
      ++blocks.back().count;
      blockOf[s] = int(blocks.size()) - 1;
    }
  }
};

void ProbeBaker::traceLattice(const ProbeTask& task, const RotationBlocks& rotations, int s, SampleColumns& columns,
                              std::vector<PunctualAtProbe::Arrival>* direct, RayCounts* counts,
                              ProbeSamples* samples, DistanceMomentsAccumulator* distances,
                              SharedReflections* shared, int sharedSlot) const {
  const int rays = settings_.rays;
  thread_local std::vector<FirstReflection> firstReflections;
  thread_local std::vector<Eigen::Vector3f> reflected, reflectedSky;
  if (shared) {
    firstReflections.resize(rays);
    reflected.resize(rays);
    reflectedSky.resize(rays);
  }
  thread_local std::vector<Eigen::Vector3f> radiance, bounced;
  thread_local std::vector<float> sky;
  radiance.resize(rays);
  bounced.resize(rays);
  sky.resize(rays);
  const RotationBlocks::Block& block = rotations.blocks[rotations.blockOf[s]];
  const std::vector<Eigen::Vector3f>& dirs = directions_[block.rotation];
  const int within = s - block.first;
  const ProbeView view = directView_.at(task.position, rays);
  thread_local std::vector<float> hitDistance;
  hitDistance.resize(rays);
  const int skyParts = (rotations.width - 4) / 3;
  integrator_.trace(task.position, task.id, dirs.data(), rays, radiance.data(), sky.data(), counts, &view,
                    distances ? hitDistance.data() : nullptr, skyParts > 1 ? bounced.data() : nullptr,
                    shared ? firstReflections.data() : nullptr, shared ? reflected.data() : nullptr,
                    shared && skyParts > 1 ? reflectedSky.data() : nullptr);
  if (shared) shared->record(sharedSlot, firstReflections.data(), reflected.data(), reflectedSky.data());
  if (distances && !distanceWeights_.empty())
    distances->add(distanceWeights_.at(std::size_t(block.rotation)), hitDistance.data());
  else if (distances)
    distances->add(dirs.data(), hitDistance.data(), rays);
  const int base = rotations.width * block.first;
  for (int r = 0; r < rays; ++r) {
    const Eigen::Vector3f value = toColorSpace(basis_.colorSpace(), radiance[r]);
    for (int c = 0; c < 3; ++c) columns(r, base + c * block.count + within) = value[c];
    columns(r, base + 3 * block.count + within) = sky[r];
    // An escaped ray brought back the sky alone (PathIntegrator): its value is the sky's.
    if (skyParts > 0)
      for (int c = 0; c < 3; ++c) columns(r, base + (4 + c) * block.count + within) = sky[r] > 0.0f ? value[c] : 0.0f;
    if (skyParts > 1) {
      const Eigen::Vector3f offSurfaces = toColorSpace(basis_.colorSpace(), bounced[r]);
      for (int c = 0; c < 3; ++c) columns(r, base + (7 + c) * block.count + within) = offSurfaces[c];
    }
  }
  if (!directView_.empty()) directView_.sample(view, task.id, direct, counts);
  if (samples) {
    samples->directions = dirs;
    samples->weights = weights_;
    samples->radiance = radiance;
    samples->visibility = sky;
  }
}

void ProbeBaker::addSharedReflections(SharedReflections& shared, int begin, int end, const RotationBlocks& rotations,
                                      SampleColumns& columns, std::vector<ProbeSamples>* samples) const {
  shared.share();
  const bool skyBounced = rotations.width > 7;
  const auto addToProbe = [&](int s) {
    const RotationBlocks::Block& block = rotations.blocks[rotations.blockOf[s]];
    const int within = s - block.first;
    const int base = rotations.width * block.first;
    ProbeSamples* probeSamples = samples ? &(*samples)[rotations.order[s]] : nullptr;
    for (int r = 0; r < settings_.rays; ++r) {
      const Eigen::Vector3f light = shared.reflected(s - begin, r);
      const Eigen::Vector3f value = toColorSpace(basis_.colorSpace(), light);
      for (int c = 0; c < 3; ++c) columns(r, base + c * block.count + within) += value[c];
      if (skyBounced) {
        const Eigen::Vector3f sky = toColorSpace(basis_.colorSpace(), shared.skyBounced(s - begin, r));
        for (int c = 0; c < 3; ++c) columns(r, base + (7 + c) * block.count + within) += sky[c];
      }
      if (probeSamples) probeSamples->radiance[std::size_t(r)] += light;
    }
  };
  // Isolated as the tracing is: a thread waiting here must not start another brick, whose bake
  // would reuse this thread's sample store.
  tbb::this_task_arena::isolate([&] { tbb::parallel_for(begin, end, addToProbe); });
}

void ProbeBaker::projectLattice(const SampleColumns& columns, const RotationBlocks& rotations, float* coefficients,
                                float* visibility, float* skyDirect, float* skyBounced) const {
  // Each coefficient is a dot product of an operator row with a probe's samples, written
  // straight to the output: the brick's operator-times-samples product, coefficient by
  // coefficient. Eigen's general product cost two and a half times as much here, most of it
  // repacking these short, wide sample blocks on every call.
  auto project = [&](const auto& fromSamples, int column, int functions, float scale, float* out) {
    const auto samples = columns.col(column);
    for (int f = 0; f < functions; ++f) out[f] = fromSamples.row(f).dot(samples) * scale;
  };
  for (const RotationBlocks::Block& block : rotations.blocks) {
    const int base = rotations.width * block.first;
    for (const ChannelGroup& group : groups_) {
      const auto& fromSamples = group.fromSamples[block.rotation];
      for (int c = 0; c < group.channelCount; ++c) {
        const int channel = group.firstChannel + c;
        const int offset = basis_.coefficientOffset(channel);
        for (int within = 0; within < block.count; ++within) {
          const std::size_t out = std::size_t(rotations.order[block.first + within]) * coefficientsPerProbe_ + offset;
          project(fromSamples, base + channel * block.count + within, group.functions, 1.0f, coefficients + out);
          if (skyDirect)
            project(fromSamples, base + (4 + channel) * block.count + within, group.functions, 1.0f, skyDirect + out);
          if (skyBounced)
            project(fromSamples, base + (7 + channel) * block.count + within, group.functions, 1.0f, skyBounced + out);
        }
      }
    }
    for (int within = 0; within < block.count; ++within)
      project(groups_[0].fromSamples[block.rotation], base + 3 * block.count + within, visibilityPerProbe_,
              float(visibilityScale()),
              visibility + std::size_t(rotations.order[block.first + within]) * visibilityPerProbe_);
  }
}

void ProbeBaker::projectExpansion(const Eigen::MatrixXd ChannelGroup::*fromExpansion,
                                  const Eigen::Ref<const Eigen::MatrixXd>& expansion, int p, float* coefficients,
                                  bool accumulate) const {
  for (const ChannelGroup& group : groups_) {
    const Eigen::MatrixXd result =
        group.*fromExpansion * expansion.middleCols(group.firstChannel * p, group.channelCount * p);
    for (int c = 0; c < group.channelCount; ++c) {
      const int offset = basis_.coefficientOffset(group.firstChannel + c);
      for (int q = 0; q < p; ++q) {
        float* out = coefficients + std::size_t(q) * coefficientsPerProbe_ + offset;
        for (int f = 0; f < group.functions; ++f) {
          if (accumulate)
            out[f] += float(result(f, c * p + q));
          else
            out[f] = float(result(f, c * p + q));
        }
      }
    }
  }
}

void ProbeBaker::projectLatticeExpansion(Eigen::MatrixXd& latticeExpansion, int p, float* coefficients, float* visibility,
                                         float* skyDirect, float* skyBounced) const {
  // The lattices' means → coefficients, through the operator the direct-view samples take.
  std::fill_n(coefficients, std::size_t(p) * coefficientsPerProbe_, 0.0f);
  latticeExpansion.middleCols(3 * p, p) *= visibilityScale();
  projectExpansion(&ChannelGroup::fromDirect, latticeExpansion, p, coefficients, false);
  if (skyDirect) {
    std::fill_n(skyDirect, std::size_t(p) * coefficientsPerProbe_, 0.0f);
    projectExpansion(&ChannelGroup::fromDirect, latticeExpansion.middleCols(4 * p, 3 * p), p, skyDirect, false);
  }
  if (skyBounced) {
    std::fill_n(skyBounced, std::size_t(p) * coefficientsPerProbe_, 0.0f);
    projectExpansion(&ChannelGroup::fromDirect, latticeExpansion.middleCols(7 * p, 3 * p), p, skyBounced, false);
  }
  const Eigen::MatrixXd seen = groups_[0].fromDirect * latticeExpansion.middleCols(3 * p, p);
  for (int q = 0; q < p; ++q)
    for (int f = 0; f < visibilityPerProbe_; ++f) visibility[std::size_t(q) * visibilityPerProbe_ + f] = float(seen(f, q));
}

void ProbeBaker::constrainNonNegative(int p, float* coefficients, float* visibility) const {
  // The linear coefficients carry the moments m = G·c; re-solve them with c ≥ 0. Only
  // quantities that cannot be negative are constrained: RGB channels, luminance Y and sky
  // visibility, not the signed chroma Co and Cg.
  auto constrain = [](const ChannelGroup& group, float* out) {
    const Eigen::VectorXd linear = Eigen::Map<Eigen::VectorXf>(out, group.functions).cast<double>();
    const Eigen::VectorXd constrained = nonNegativeProjection(group.gram, group.gram * linear);
    for (int f = 0; f < group.functions; ++f) out[f] = float(constrained[f]);
  };
  for (const ChannelGroup& group : groups_)
    for (int c = 0; c < group.channelCount; ++c) {
      const int channel = group.firstChannel + c;
      if (basis_.colorSpace() == ColorSpace::YCoCg && channel != 0) continue;
      for (int q = 0; q < p; ++q)
        constrain(group, coefficients + std::size_t(q) * coefficientsPerProbe_ + basis_.coefficientOffset(channel));
    }
  for (int q = 0; q < p; ++q) constrain(groups_[0], visibility + std::size_t(q) * visibilityPerProbe_);
}

int ProbeBaker::skyPartsKept(const float* skyDirect, const float* skyBounced) const {
  if (skyDirect && !keepsSkyDirect_) throw std::logic_error("ProbeBaker::bake: this bake keeps no directly seen sky");
  if (skyBounced && (!keepsSkyBounced_ || !skyDirect))
    throw std::logic_error("ProbeBaker::bake: the sky's light off surfaces is kept with the directly seen sky, where "
                           "paths reflect");
  return skyBounced ? 2 : skyDirect ? 1 : 0;
}

// What the probes of one bake() call write to, shared by the threads that trace them.
struct ProbeBaker::BrickPass {
  const std::vector<ProbeTask>& tasks;
  const RotationBlocks& rotations;
  SampleColumns& columns;
  std::vector<ProbeSamples>* samples;
  const DistanceMomentsOutput& distances;
  ArrivalExpansion &punctualArrivals, &directArrivals, &skyArrivals;
  Eigen::MatrixXd& latticeExpansion;  // adaptive convergence's
  int skyParts;
  bool punctualAtProbe;       // the punctual lights each probe sees are added as deltas
  SharedReflections* shared;  // with shared reflections, and the first probe of the group being traced
  int groupStart = 0;
};

void ProbeBaker::traceProbe(BrickPass& pass, int s, RayCounts* counts, RoundTally* tally,
                            DistanceMomentsAccumulator* moments) const {
  const int taskIndex = pass.rotations.order[s];
  const ProbeTask& task = pass.tasks[taskIndex];
  ProbeSamples* probeSamples = pass.samples ? &(*pass.samples)[taskIndex] : nullptr;
  std::vector<PunctualAtProbe::Arrival> lights, direct;
  if (pass.punctualAtProbe) lights = punctual_.visibleLights(task.position, counts);
  if (moments) moments->reset();
  if (settings_.convergence.adaptive()) {
    const Rounds rounds = traceRounds(task, lights, &direct, pass.latticeExpansion, taskIndex, int(pass.tasks.size()),
                                      pass.skyParts, counts, probeSamples, moments);
    tally->add(rounds.rays, !rounds.converged);
  } else {
    traceLattice(task, pass.rotations, s, pass.columns, &direct, counts, probeSamples, moments, pass.shared,
                 s - pass.groupStart);
    tally->add(settings_.rays, false);
  }
  if (moments) moments->write(pass.distances.values + std::size_t(taskIndex) * pass.distances.layout.valuesPerProbe());
  pass.punctualArrivals.add(lights, taskIndex, basis_.colorSpace());
  pass.directArrivals.add(direct, taskIndex, basis_.colorSpace());
  if (pass.skyParts > 0) pass.skyArrivals.add(DirectView::fromSky(direct), taskIndex, basis_.colorSpace());
  if (probeSamples) {
    probeSamples->punctual = std::move(lights);
    probeSamples->direct = std::move(direct);
  }
}

void ProbeBaker::bake(const std::vector<ProbeTask>& tasks, float* coefficients, float* visibility, RayCounts* counts,
                      std::vector<ProbeSamples>* samples, RoundTally* tally,
                      const DistanceMomentsOutput& distances, float* skyDirect, float* skyBounced) const {
  const int p = int(tasks.size());
  const bool adaptive = settings_.convergence.adaptive();
  const int skyParts = skyPartsKept(skyDirect, skyBounced);
  const bool keepSky = skyParts > 0;
  if (samples) samples->assign(p, {});
  const RotationBlocks rotations(tasks, skyParts);
  // Kept from brick to brick on each thread: a brick's samples are megabytes.
  thread_local ScratchBuffer<float> sampleStore;
  const int columnRays = adaptive ? 0 : settings_.rays;
  SampleColumns columns(sampleStore.reserve(std::size_t(columnRays) * rotations.width * std::size_t(p)), columnRays,
                        rotations.width * p);
  const bool punctualAtProbe = settings_.transport.directPunctual && !punctual_.empty();
  ArrivalExpansion punctualArrivals(*punctualExpansion_, punctualAtProbe ? p : 0);
  ArrivalExpansion directArrivals(*directExpansion_, directView_.empty() ? 0 : p);
  ArrivalExpansion skyArrivals(*directExpansion_, keepSky && directView_.samplesSky() ? p : 0);
  // Adaptive convergence: the lattices' expansion per probe (SH, or for radiance the basis's
  // moments), of the three channels, of sky visibility and of the kept parts of the sky's
  // channels (count × (4 + 3 parts)p, channel-major like directArrivals).
  Eigen::MatrixXd latticeExpansion;
  if (adaptive) latticeExpansion.setZero(directExpansion_->count(), rotations.width * p);
  std::optional<SharedReflections> shared;
  if (!adaptive && settings_.sharedReflectionCell > 0.0f)
    shared.emplace(settings_.sharedReflectionCell, settings_.rays, skyParts > 1);
  BrickPass pass{tasks,          rotations,      columns,          samples,  distances,
                 punctualArrivals, directArrivals, skyArrivals,    latticeExpansion, skyParts,
                 punctualAtProbe, shared ? &*shared : nullptr};

  // A probe's samples depend on nothing but the probe, so they are traced a few probes per task:
  // a volume of a few bricks keeps every thread busy to the end, where whole bricks would leave
  // one thread finishing the last brick alone. Isolated, so that a thread waiting here takes
  // only this brick's probes, never another brick, whose bake would reuse this thread's store.
  std::mutex countsMutex;
  const auto traceProbes = [&](int begin, int end) {
    tbb::this_task_arena::isolate([&] {
      tbb::parallel_for(tbb::blocked_range<int>(begin, end, kProbesPerTask), [&](const tbb::blocked_range<int>& range) {
        RayCounts rangeCounts;
        RoundTally rangeTally;
        std::optional<DistanceMomentsAccumulator> moments;
        if (distances.values) moments.emplace(distances.layout);
        for (int s = range.begin(); s < range.end(); ++s)
          traceProbe(pass, s, &rangeCounts, &rangeTally, moments ? &*moments : nullptr);
        const std::lock_guard<std::mutex> lock(countsMutex);
        *counts += rangeCounts;  // integers: the same totals in any order
        if (tally) *tally += rangeTally;
      });
    });
  };
  if (shared)
    traceInGroups(*shared, p, rotations, columns, samples, &pass.groupStart, traceProbes);
  else
    traceProbes(0, p);

  const auto projectionStart = std::chrono::steady_clock::now();
  if (adaptive)
    projectLatticeExpansion(latticeExpansion, p, coefficients, visibility, skyDirect, skyBounced);
  else
    projectLattice(columns, rotations, coefficients, visibility, skyDirect, skyBounced);
  projectArrivals(punctualArrivals, directArrivals, skyArrivals, p, coefficients, skyDirect);
  if (settings_.projection.nonNegative) constrainNonNegative(p, coefficients, visibility);
  projectionNanoseconds_ += std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() -
                                                                                 projectionStart)
                                .count();
}

void ProbeBaker::traceInGroups(SharedReflections& shared, int p, const RotationBlocks& rotations,
                               SampleColumns& columns, std::vector<ProbeSamples>* samples, int* groupStart,
                               const std::function<void(int, int)>& traceProbes) const {
  // Probes share within groups of consecutive ones (in rotation order) whose samples fit
  // SharedReflections' memory; a group is traced whole before its reflections are shared.
  const int group = SharedReflections::groupProbes(settings_.rays, rotations.width > 7);
  for (*groupStart = 0; *groupStart < p; *groupStart += group) {
    const int groupEnd = std::min(p, *groupStart + group);
    shared.startGroup(groupEnd - *groupStart);
    traceProbes(*groupStart, groupEnd);
    addSharedReflections(shared, *groupStart, groupEnd, rotations, columns, samples);
  }
}

void ProbeBaker::projectArrivals(const ArrivalExpansion& punctual, const ArrivalExpansion& direct,
                                 const ArrivalExpansion& sky, int p, float* coefficients, float* skyDirect) const {
  if (punctual.any) projectExpansion(&ChannelGroup::fromPunctual, punctual.values, p, coefficients, true);
  if (direct.any) projectExpansion(&ChannelGroup::fromDirect, direct.values, p, coefficients, true);
  if (sky.any) projectExpansion(&ChannelGroup::fromDirect, sky.values, p, skyDirect, true);
}

}  // namespace baker
