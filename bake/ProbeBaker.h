#pragma once
#include <Eigen/Core>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "bake/DirectView.h"
#include "bake/PathIntegrator.h"
#include "bake/ProbeConvergence.h"
#include "bake/PunctualAtProbe.h"
#include "bake/SharedReflections.h"
#include "bake/Transport.h"
#include "basis/Basis.h"
#include "basis/DirectionSet.h"
#include "basis/GgxLobe.h"
#include "basis/GramOperators.h"
#include "basis/StackedFunctions.h"
#include "basis/StoredSignal.h"
#include "scene/RayTracer.h"
#include "scene/Scene.h"
#include "volume/DistanceMoments.h"

namespace baker {

// How ray samples become coefficients beyond the default linear projection.
struct ProjectionOptions {
  BandWindow window;         // Hann window on the SH bands (paper eq. 8) against ringing
  bool nonNegative = false;  // coefficients ≥ 0 by a per-probe constrained solve (NonNegativeProjection)
  StoredSignal signal = StoredSignal::Irradiance;
};

struct BakeSettings {
  int rays = 256;  // a fixed count, or with adaptive convergence the size of round 0's lattices
  // Texels per side of each probe's distance map (volume/DistanceMoments.h); 0: none.
  int distanceMapSize = 0;
  // Side of the cells in which a brick's probes share what their paths bring back from surfaces
  // (SharedReflections); 0: each probe keeps its own.
  float sharedReflectionCell = 0.0f;
  int distanceValuesPerProbe() const { return DistanceMapLayout::baked(distanceMapSize, 0.0).valuesPerProbe(); }
  ConvergenceSettings convergence;
  ProjectionOptions projection;
  TransportSettings transport;
};

// One probe to bake: where it is, the id its random numbers derive from, and which rotation of
// the direction set it traces.
struct ProbeTask {
  Eigen::Vector3f position{0.0f, 0.0f, 0.0f};
  std::uint64_t id = 0;
  int rotation = 0;
};

// Where a bake writes each probe's distance moments (volume/DistanceMoments.h): values per task,
// layout.valuesPerProbe() of them. None when `values` is null.
struct DistanceMomentsOutput {
  DistanceMapLayout layout{0, 0.0};
  float* values = nullptr;
};

// What a probe's rays brought back, for tools that look at one probe (`baker probe`).
struct ProbeSamples {
  std::vector<Eigen::Vector3f> directions;
  std::vector<double> weights;  // quadrature weights, Σ = 4π
  std::vector<Eigen::Vector3f> radiance;  // the lattice's MIS share of what each ray brought back
  std::vector<float> visibility;
  std::vector<PunctualAtProbe::Arrival> punctual;  // lights reaching the probe (direct-punctual)
  std::vector<DirectView::Arrival> direct;         // what DirectView sampled, MIS-weighted
};

// E(n) = Σ L(ω) max(0, n·ω) w over the probe's rays, plus E⊥ max(0, n·ω) of each punctual
// light and of each direct-view sample: the irradiance the samples imply, before any basis.
Eigen::Vector3f sampledIrradiance(const ProbeSamples& samples, const Eigen::Vector3f& normal);

// The GGX-weighted mean radiance S the samples imply, before any basis (GgxLobe): the rays'
// radiance weighted by w ρ(ω)(n·ω)⁺ over the sum of those weights, plus each punctual and
// direct-view arrival weighted by ρ(ω)(n·ω)⁺ over the lobe's albedo A. The rays resolve the
// lobe only where it is wider than their spacing; `rayCoverage` is Σ w ρ(ω)(n·ω)⁺ / A over the
// rays: near 1 when they do, 0 for the mirror (whose reference no set of rays holds).
struct SampledSpecular {
  Eigen::Vector3f value;
  double rayCoverage = 0.0;
  double albedo = 0.0;  // A, by the lobe's own quadrature
};
SampledSpecular sampledSpecular(const ProbeSamples& samples, const GgxLobe& lobe);

// Bakes batches of probes (a brick) into basis coefficients. Each probe traces a lattice of
// `rays` spherical Fibonacci directions, turned by one of a few rotations drawn from the seed:
// each seed traces its own directions, so that bakes of different seeds are independent and
// their spread measures the error, and neighbouring probes of a grid trace differently turned
// sets, so that the aliasing of one set does not repeat as one pattern across the volume. What
// the probe sees directly that is small and bright is sampled by importance besides
// (DirectView) and combined with the lattice by MIS. Each rotation has its precomputed
// projection: samples → SH fit of the resolvable order → clamped-cosine convolution → exact
// projection into the basis. A batch costs one matrix product per rotation and channel group.
// Punctual lights seen by the probe, and the direct-view samples, enter as SH deltas through a
// second precomputed product. With adaptive convergence a probe traces rounds of lattices that
// double until its irradiance is known well enough (ConvergenceSettings); each lattice turns by
// a rotation of its own, drawn from (seed, probe, lattice), and enters as SH deltas like the
// direct-view samples, so that no lattice needs an operator of its own.
//
// A radiance volume (StoredSignal) fits the radiance itself: each rotation's samples by weighted
// least squares in the basis, so that whatever the functions can hold (a constant sky) comes out
// exactly, and the deltas by their exact moments f(ω)·E through G⁻¹, where SH truncation would
// blur them. Adaptive rounds sum the lattices' moments and their sampled Gram matrix BᵀWB per
// probe and solve the same least squares over the probe's own rays.
class ProbeBaker {
 public:
  // Which sampler made a volume, recorded in its metadata (setting "sampler") so that `validate`
  // says why volumes of two versions differ: the lattice's rotations drawn from the seed, the
  // direct view sampled by importance and combined by MIS, path vertices aiming at lights.
  // Volumes before it record none (one fixed set of eight rotations, the lattice alone). /2:
  // the operators hold exact zeros where /1 held quadrature rounding (±1e-17), so coefficients
  // that are zero in exact arithmetic are stored as zeros; nothing else differs. /3: a path
  // vertex draws its random numbers two from one scrambled counter (PathRandom::uniformPair), so
  // paths take other, equally distributed, numbers than /2's from their first hit's next events on.
  static constexpr const char* kSampler = "seeded-lattice+direct-view-mis+aimed-bounces/3";
  // With adaptive convergence: rounds of two lattices that double, each in the probe's own
  // rotation (ConvergenceSettings).
  static constexpr const char* kAdaptiveSampler = "doubling-lattice-rounds+direct-view-mis+aimed-bounces/3";
  static const char* samplerName(const BakeSettings& settings) {
    return settings.convergence.adaptive() ? kAdaptiveSampler : kSampler;
  }

  // The sample fit never goes beyond this SH order: the clamped cosine's band 16 is 0.15 % of
  // band 0, and the fit's cost grows with the square of the SH count.
  static constexpr int kMaxSampleShOrder = 16;
  // Fixed lattices up to this size have their distance-map weights worked out once per rotation
  // (about 9 weights a ray, 12 bytes each, per rotation); larger ones work them out ray by ray.
  static constexpr int kMostRaysWithDistanceWeights = 1 << 16;

  ProbeBaker(const Scene& scene, const RayTracer& tracer, const Basis& basis, const BakeSettings& settings,
             int rotations);
  ~ProbeBaker();

  int coefficientsPerProbe() const { return coefficientsPerProbe_; }
  // Sky visibility is stored like channel 0's signal: for irradiance divided by π,
  // V(n) = (1/π) ∫ V max(0, n·ω) dω; for radiance V(ω) itself.
  int visibilityPerProbe() const { return visibilityPerProbe_; }
  // Whether bake() can keep each probe's directly seen sky apart (its `skyDirect`): when the sky
  // lights the bake, and the coefficients are linear in the samples (not the non-negative fit).
  bool keepsSkyDirect() const { return keepsSkyDirect_; }
  // Whether it can keep apart, too, the sky's light off surfaces (its `skyBounced`): when it keeps
  // the directly seen sky and paths reflect.
  bool keepsSkyBounced() const { return keepsSkyBounced_; }
  int rotations() const { return int(directions_.size()); }
  const std::vector<Eigen::Vector3f>& directions(int rotation) const { return directions_[rotation]; }
  int shOrder() const { return shOrder_; }
  double conditionNumber() const { return condition_; }
  const PathIntegrator& integrator() const { return integrator_; }
  // Time spent in the projection (matrix products and constrained solves), summed over threads.
  double projectionSeconds() const { return projectionNanoseconds_.load() * 1e-9; }

  // coefficients: tasks.size() × coefficientsPerProbe(); visibility: × visibilityPerProbe().
  // `samples`, when given, receives each task's samples; `tally` hears how many lattice
  // directions the probes took; `distances`, when it has values, each probe's distance moments
  // from its lattice rays (no ray is traced for them); `skyDirect`, when given (keepsSkyDirect()),
  // receives tasks.size() × coefficientsPerProbe(): the coefficients of the sky alone as the
  // probe saw it directly, the lattice's escaped rays and the direct view's sky samples, by the
  // same projection, so that coefficients − skyDirect is the rest of the light. `skyBounced`,
  // when given with it (keepsSkyBounced()), receives as many: the coefficients of the sky's light
  // that reached the probe off surfaces (PathIntegrator's skyBounced), the same way.
  void bake(const std::vector<ProbeTask>& tasks, float* coefficients, float* visibility, RayCounts* counts,
            std::vector<ProbeSamples>* samples = nullptr, RoundTally* tally = nullptr,
            const DistanceMomentsOutput& distances = {}, float* skyDirect = nullptr,
            float* skyBounced = nullptr) const;

 private:
  struct ChannelGroup;
  struct ArrivalExpansion;
  struct RotationBlocks;
  // A fixed lattice's samples, per brick: rays × 4p (RotationBlocks says which column is whose).
  using SampleColumns = Eigen::Map<Eigen::MatrixXf>;
  // Each group's operators from the rotated lattices (and the deltas' expansion) to coefficients.
  void buildIrradianceOperators(const std::vector<DirectionSet>& sets);
  void buildRadianceOperators(const std::vector<DirectionSet>& sets);
  // The last SH band, up to `order`, whose columns in some group's operator are not all zero.
  int lastBandRead(const Eigen::MatrixXd ChannelGroup::*shOperator, int order) const;
  struct Rounds {
    std::int64_t rays;
    bool converged;
  };
  // One probe's rounds, until it converges: its lattices' radiance is summed as SH into
  // `latticeExpansion` (column c·batchSize + taskIndex for channel c, 3 for sky visibility), its
  // direct-view samples into `direct`, both as means over all its rays; and into `samples`
  // when given. With `skyParts` 1 or 2, columns (4 + c)·batchSize + taskIndex sum channel c of
  // the rays that escaped; with 2, columns (7 + c)·batchSize + taskIndex the sky's light off
  // surfaces.
  Rounds traceRounds(const ProbeTask& task, const std::vector<PunctualAtProbe::Arrival>& lights,
                     std::vector<PunctualAtProbe::Arrival>* direct, Eigen::MatrixXd& latticeExpansion, int taskIndex,
                     int batchSize, int skyParts, RayCounts* counts, ProbeSamples* samples,
                     DistanceMomentsAccumulator* distances) const;
  void fitRoundsByLeastSquares(const Eigen::MatrixXd& sampledGram, Eigen::MatrixXd& latticeExpansion, int taskIndex,
                               int batchSize, int skyParts) const;
  // The probe's fixed lattice, traced into its columns, with its direct-view samples.
  void traceLattice(const ProbeTask& task, const RotationBlocks& rotations, int s, SampleColumns& columns,
                    std::vector<PunctualAtProbe::Arrival>* direct, RayCounts* counts, ProbeSamples* samples,
                    DistanceMomentsAccumulator* distances, SharedReflections* shared, int sharedSlot) const;
  struct BrickPass;
  // Probe s (in rotation order) of a bake() call, traced into what `pass` holds for it.
  void traceProbe(BrickPass& pass, int s, RayCounts* counts, RoundTally* tally,
                  DistanceMomentsAccumulator* moments) const;
  // Traces the p probes by traceProbes(begin, end) in groups that share their reflections,
  // *groupStart the first probe of the group being traced.
  void traceInGroups(SharedReflections& shared, int p, const RotationBlocks& rotations, SampleColumns& columns,
                     std::vector<ProbeSamples>* samples, int* groupStart,
                     const std::function<void(int, int)>& traceProbes) const;
  // The punctual lights', direct-view and directly seen sky's arrivals, added to the coefficients.
  void projectArrivals(const ArrivalExpansion& punctual, const ArrivalExpansion& direct, const ArrivalExpansion& sky,
                       int p, float* coefficients, float* skyDirect) const;
  // Shares the reflections of probes [begin, end) (in rotation order), recorded in `shared`, and
  // adds to each lattice ray's columns what it reflects of its cell's mean.
  void addSharedReflections(SharedReflections& shared, int begin, int end, const RotationBlocks& rotations,
                            SampleColumns& columns, std::vector<ProbeSamples>* samples) const;
  void projectLattice(const SampleColumns& columns, const RotationBlocks& rotations, float* coefficients,
                      float* visibility, float* skyDirect, float* skyBounced) const;
  void projectLatticeExpansion(Eigen::MatrixXd& latticeExpansion, int p, float* coefficients, float* visibility,
                               float* skyDirect, float* skyBounced) const;
  // Coefficients of arrivals expanded in an expansion's functions (count × 3p) through each
  // group's operator `fromExpansion`, added to or written over `coefficients`.
  void projectExpansion(const Eigen::MatrixXd ChannelGroup::*fromExpansion,
                        const Eigen::Ref<const Eigen::MatrixXd>& expansion, int p, float* coefficients,
                        bool accumulate) const;
  void constrainNonNegative(int p, float* coefficients, float* visibility) const;
  // How many parts of the sky bake() keeps apart: 0, 1 (seen directly), 2 (and off surfaces);
  // std::logic_error for a part this bake cannot keep.
  int skyPartsKept(const float* skyDirect, const float* skyBounced) const;
  // Sky visibility's factor after the projection: 1/π turns irradiance of V into its cosine-weighted mean.
  double visibilityScale() const {
    return settings_.projection.signal == StoredSignal::Radiance ? 1.0 : 1.0 / M_PI;
  }

  const Basis& basis_;
  BakeSettings settings_;
  PathIntegrator integrator_;
  PunctualAtProbe punctual_;
  DirectView directView_;
  std::vector<std::vector<Eigen::Vector3f>> directions_;  // per rotation
  std::vector<DirectionSet> roundLattices_;               // unturned, per round (adaptive convergence)
  std::vector<double> weights_;
  std::vector<DistanceLatticeWeights> distanceWeights_;  // per rotation, for fixed lattices' distance moments
  // Deltas (lights, direct-view samples, adaptive lattices) are expanded in these functions before
  // each group's operator: SH for irradiance (up to the last band the operators read, of the
  // punctual lights' order and of the lattice's), for radiance the basis's own functions
  // (`ownFunctions_`).
  SphericalHarmonics directHarmonics_{0}, punctualHarmonics_{0};
  StackedFunctions ownFunctions_;
  const SphericalFunctions* punctualExpansion_ = nullptr;
  const SphericalFunctions* directExpansion_ = nullptr;
  std::vector<ChannelGroup> groups_;
  int coefficientsPerProbe_ = 0;
  int visibilityPerProbe_ = 0;
  bool keepsSkyDirect_ = false, keepsSkyBounced_ = false;
  int shOrder_ = 0;
  double condition_ = 0.0;
  mutable std::atomic<std::int64_t> projectionNanoseconds_{0};
};

}  // namespace baker
