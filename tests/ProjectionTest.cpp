#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <random>

#include "basis/DirectionSet.h"
#include "basis/ProjectionOperator.h"
#include "basis/SphericalHarmonics.h"
#include "common/Error.h"

namespace baker {
namespace {

TEST(Projection, ShL2OperatorReproducesAFunctionInItsSpan) {
  const SphericalHarmonics sh(2);
  const DirectionSet dirs = sphericalFibonacci(256);
  const ProjectionOperator op = leastSquaresProjection(sh, dirs, "sh-l2");
  ASSERT_EQ(op.matrix.rows(), 9);
  ASSERT_EQ(op.matrix.cols(), 256);
  EXPECT_LT(op.conditionNumber, 2.0);  // 256 Fibonacci points resolve nine harmonics almost perfectly

  std::mt19937 rng(7);
  std::normal_distribution<double> normal;
  for (int trial = 0; trial < 5; ++trial) {
    Eigen::VectorXd c(9);
    for (int i = 0; i < 9; ++i) c[i] = normal(rng);
    Eigen::VectorXd samples(256), y(9);
    for (int k = 0; k < 256; ++k) {
      sh.evaluate(dirs.directions[k], y.data());
      samples[k] = y.dot(c);
    }
    EXPECT_LT((op.matrix * samples - c).cwiseAbs().maxCoeff(), 1e-12);
  }
}

TEST(Projection, RefusesTooFewDirectionsWithAClearMessage) {
  const SphericalHarmonics sh(8);
  try {
    leastSquaresProjection(sh, sphericalFibonacci(40), "sh-l8");
    FAIL() << "81 functions from 40 directions must be refused";
  } catch (const NumericalError& e) {
    EXPECT_NE(std::string(e.what()).find("sh-l8"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("more rays"), std::string::npos) << e.what();
  }
}

// A bake checks the conditioning of its first rotation's SH fit only: a rotated set's sampled
// Gram matrix is D·G·Dᵀ with D orthogonal, so it has the same spectrum.
TEST(Projection, RotatingTheDirectionsKeepsTheFitsConditioning) {
  const SphericalHarmonics sh(7);
  const DirectionSet set = sphericalFibonacci(256);
  const double unrotated = SampledFit(sh, set, "sh-l7").conditionNumber();
  std::mt19937 rng(3);
  std::normal_distribution<double> normal;
  for (int trial = 0; trial < 4; ++trial) {
    const Eigen::Quaterniond q(normal(rng), normal(rng), normal(rng), normal(rng));
    DirectionSet turned = set;
    for (Eigen::Vector3d& d : turned.directions) d = q.normalized() * d;
    const double rotated = SampledFit(sh, turned, "sh-l7").conditionNumber();
    EXPECT_NEAR(rotated, unrotated, 1e-9 * unrotated) << "rotation " << trial;
    // Skipping the check changes nothing else about the fit.
    const Eigen::MatrixXd left = Eigen::MatrixXd::Random(3, sh.count());
    const SampledFit checked(sh, turned, "sh-l7"),
        unchecked(sh, turned, "sh-l7", SampledFit::Conditioning::CheckedByRotation);
    EXPECT_EQ(unchecked.conditionNumber(), 0.0);
    EXPECT_TRUE(checked.after(left) == unchecked.after(left));
  }
}

TEST(DirectionSet, FibonacciPointsAreUnitAndWeightsSumTo4Pi) {
  const DirectionSet dirs = sphericalFibonacci(1000);
  double total = 0.0;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (std::size_t k = 0; k < dirs.size(); ++k) {
    EXPECT_NEAR(dirs.directions[k].norm(), 1.0, 1e-14);
    total += dirs.weights[k];
    mean += dirs.directions[k];
  }
  EXPECT_NEAR(total, 4 * M_PI, 1e-12);
  EXPECT_LT(mean.norm() / 1000, 1e-3);  // evenly spread: no net direction
}

}  // namespace
}  // namespace baker
