#include "bake/Baker.h"

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <Eigen/Core>
#include <chrono>
#include <vector>

#include "bake/DirectionSet.h"
#include "bake/ProbeTracer.h"
#include "bake/GramOperators.h"
#include "bake/NonNegativeProjection.h"
#include "common/Error.h"

namespace baker {
namespace {

// Consecutive colour channels that share one function set are projected together: for an
// RGB basis that is one product over all three channels of a brick.
struct ChannelGroup {
  int firstChannel = 0;
  int channelCount = 0;
  Eigen::MatrixXf projection;  // radiance samples → irradiance coefficients: functions × directions
  Eigen::MatrixXd gram;        // for the non-negative solve
};

std::vector<ChannelGroup> groupChannels(const Basis& basis, const DirectionSet& directions, int shOrder,
                                        const BandWindow& window, double* worstCondition) {
  std::vector<ChannelGroup> groups;
  for (int c = 0; c < 3; ++c) {
    if (c > 0 && &basis.functions(c) == &basis.functions(c - 1)) {
      ++groups.back().channelCount;
      continue;
    }
    const GramOperators ops(basis.functions(c), basis.name());
    *worstCondition = std::max(*worstCondition, ops.conditionNumber());
    groups.push_back({c, 1, ops.irradianceFromSamples(directions, shOrder, window).cast<float>(), ops.gram()});
  }
  return groups;
}

}  // namespace

Volume bakeVolume(const Scene& scene, const RayTracer& tracer, const Basis& basis, const ProbeGrid& grid, int rays,
                  BakeStats* stats, const ProjectionOptions& options) {
  if (rays <= 0) throw InputError(fmt::format("--rays must be positive, got {}", rays));
  const DirectionSet directions = sphericalFibonacci(rays);
  const auto start = std::chrono::steady_clock::now();
  double condition = 0.0;
  const int shOrder = resolvableShOrder(directions.size());
  const std::vector<ChannelGroup> groups = groupChannels(basis, directions, shOrder, options.window, &condition);
  const auto operatorsBuilt = std::chrono::steady_clock::now();
  std::vector<Eigen::Vector3f> rayDirections;
  for (const Eigen::Vector3d& d : directions.directions) rayDirections.push_back(d.cast<float>());
  const ProbeTracer probeTracer(scene, tracer, rayDirections);

  Volume volume;
  volume.grid = grid;
  volume.basisName = basis.name();
  volume.coefficientsPerProbe = basis.totalCoefficients();
  volume.coefficients.assign(std::size_t(grid.probeCount()) * volume.coefficientsPerProbe, 0.0f);

  const Eigen::Vector3i bricks = (grid.dims.array() + kBrickSize - 1) / kBrickSize;
  const int brickCount = bricks.x() * bricks.y() * bricks.z();
  const ColorSpace space = basis.colorSpace();

  tbb::parallel_for(tbb::blocked_range<int>(0, brickCount, 1), [&](const tbb::blocked_range<int>& range) {
    std::vector<Eigen::Vector3f> radiance(rays);
    for (int b = range.begin(); b < range.end(); ++b) {
      const Eigen::Vector3i brick(b % bricks.x(), (b / bricks.x()) % bricks.y(), b / (bricks.x() * bricks.y()));
      const Eigen::Vector3i lo = brick * kBrickSize;
      const Eigen::Vector3i hi = (lo.array() + kBrickSize).min(grid.dims.array());
      std::vector<std::int64_t> probes;
      for (int k = lo.z(); k < hi.z(); ++k)
        for (int j = lo.y(); j < hi.y(); ++j)
          for (int i = lo.x(); i < hi.x(); ++i) probes.push_back(grid.linearIndex(i, j, k));
      const int p = int(probes.size());

      // Samples of the brick, one column per (channel, probe): channel-major blocks so that a
      // channel group is a contiguous run of columns.
      Eigen::MatrixXf samples(rays, 3 * p);
      int column = 0;
      for (int k = lo.z(); k < hi.z(); ++k)
        for (int j = lo.y(); j < hi.y(); ++j)
          for (int i = lo.x(); i < hi.x(); ++i, ++column) {
            probeTracer.trace(grid.position(i, j, k).cast<float>(), radiance.data());
            for (int r = 0; r < rays; ++r) {
              const Eigen::Vector3f value = toColorSpace(space, radiance[r]);
              for (int c = 0; c < 3; ++c) samples(r, c * p + column) = value[c];
            }
          }

      for (const ChannelGroup& group : groups) {
        const Eigen::MatrixXf coefficients =
            group.projection * samples.middleCols(group.firstChannel * p, group.channelCount * p);
        for (int c = 0; c < group.channelCount; ++c) {
          const int offset = basis.coefficientOffset(group.firstChannel + c);
          for (int q = 0; q < p; ++q) {
            float* out = volume.coefficients.data() + probes[q] * volume.coefficientsPerProbe + offset;
            if (options.nonNegative) {
              // The linear coefficients carry the moments m = G·c; re-solve them with c ≥ 0.
              const Eigen::VectorXd linear = coefficients.col(c * p + q).cast<double>();
              const Eigen::VectorXd constrained = nonNegativeProjection(group.gram, group.gram * linear);
              for (int f = 0; f < coefficients.rows(); ++f) out[f] = float(constrained[f]);
            } else {
              for (int f = 0; f < coefficients.rows(); ++f) out[f] = coefficients(f, c * p + q);
            }
          }
        }
      }
    }
  });

  if (stats) {
    stats->probes = grid.probeCount();
    stats->bricks = brickCount;
    stats->raysPerProbe = rays;
    stats->raysTraced = grid.probeCount() * rays;
    stats->conditionNumber = condition;
    stats->shOrder = shOrder;
    stats->operatorSeconds = std::chrono::duration<double>(operatorsBuilt - start).count();
    stats->traceSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - operatorsBuilt).count();
  }
  return volume;
}

}  // namespace baker
