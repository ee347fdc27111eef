#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "basis/AmbientCubeBasis.h"
#include "basis/BasisRegistry.h"
#include "basis/DirectionSet.h"
#include "basis/ProjectionOperator.h"

namespace baker {
namespace {

TEST(AmbientCube, IsRegisteredWithItsCounts) {
  const auto basis = makeBasis("ambient-cube");
  EXPECT_EQ(basis->name(), "ambient-cube");
  EXPECT_EQ(basis->totalCoefficients(), 18);
  EXPECT_EQ(basis->coefficientsPerLookup(), 9);
  EXPECT_TRUE(basis->channelsShareFunctions());
}

TEST(AmbientCube, LobesAreClampedCosinesSquaredThatSumToOne) {
  const AmbientCubeLobes lobes;
  const DirectionSet dirs = sphericalFibonacci(500);
  double values[6];
  for (const Eigen::Vector3d& d : dirs.directions) {
    lobes.evaluate(d, values);
    double sum = 0.0;
    for (int axis = 0; axis < 3; ++axis) {
      EXPECT_EQ(values[2 * axis], std::pow(std::max(0.0, d[axis]), 2));
      EXPECT_EQ(values[2 * axis + 1], std::pow(std::max(0.0, -d[axis]), 2));
      sum += values[2 * axis] + values[2 * axis + 1];
    }
    EXPECT_NEAR(sum, 1.0, 1e-15);
  }
}

TEST(AmbientCube, LeastSquaresReproducesAFunctionInItsSpan) {
  const AmbientCubeLobes lobes;
  const DirectionSet dirs = sphericalFibonacci(256);
  const ProjectionOperator op = leastSquaresProjection(lobes, dirs, "ambient-cube");
  std::mt19937 rng(5);
  std::normal_distribution<double> normal;
  for (int trial = 0; trial < 5; ++trial) {
    Eigen::VectorXd c(6), samples(dirs.size()), values(6);
    for (int i = 0; i < 6; ++i) c[i] = normal(rng);
    for (std::size_t k = 0; k < dirs.size(); ++k) {
      lobes.evaluate(dirs.directions[k], values.data());
      samples[k] = values.dot(c);
    }
    EXPECT_LT((op.matrix * samples - c).cwiseAbs().maxCoeff(), 1e-12);
  }
}

// The fast lookup agrees with evaluating every function and reads only the three lobes facing
// d: the other nine coefficients are NaN here and must not reach the result.
TEST(AmbientCube, LookupReadsOnlyTheNineFacingCoefficients) {
  const AmbientCubeBasis basis;
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> uniform(-2.0f, 2.0f);
  float coefficients[18];
  for (float& c : coefficients) c = uniform(rng);
  for (const Eigen::Vector3d& d : sphericalFibonacci(300).directions) {
    const Eigen::Vector3f expected = basis.Basis::reconstruct(coefficients, d);
    float poisoned[18];
    for (int c = 0; c < 3; ++c)
      for (int lobe = 0; lobe < 6; ++lobe) {
        const int axis = lobe / 2;
        const bool facing = (lobe % 2 == 0) == (d[axis] >= 0.0);
        poisoned[6 * c + lobe] = facing ? coefficients[6 * c + lobe] : std::numeric_limits<float>::quiet_NaN();
      }
    const Eigen::Vector3f fast = basis.reconstruct(poisoned, d);
    EXPECT_LT((fast - expected).cwiseAbs().maxCoeff(), 1e-6f) << d.transpose();
  }
}

}  // namespace
}  // namespace baker
