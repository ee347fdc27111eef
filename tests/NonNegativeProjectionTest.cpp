#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

#include "basis/BasisRegistry.h"
#include "basis/NonNegativeProjection.h"

namespace baker {
namespace {

Eigen::MatrixXd randomSpd(int n, std::mt19937& rng) {
  std::normal_distribution<double> normal;
  Eigen::MatrixXd a(n + 3, n);
  for (int i = 0; i < a.rows(); ++i)
    for (int j = 0; j < n; ++j) a(i, j) = normal(rng);
  return a.transpose() * a;
}

TEST(NonNegativeProjection, EqualsTheLinearSolveWhenThatIsAlreadyNonNegative) {
  std::mt19937 rng(1);
  const Eigen::MatrixXd g = randomSpd(8, rng);
  const Eigen::VectorXd expected = Eigen::VectorXd::LinSpaced(8, 0.5, 2.0);
  const Eigen::VectorXd c = nonNegativeProjection(g, g * expected);
  EXPECT_LT((c - expected).cwiseAbs().maxCoeff(), 1e-10);
}

// On random problems the result satisfies the optimality (KKT) conditions: c ≥ 0, the
// gradient m − Gc ≤ 0 wherever c = 0 and = 0 wherever c > 0.
TEST(NonNegativeProjection, SatisfiesTheOptimalityConditions) {
  std::mt19937 rng(2);
  std::normal_distribution<double> normal;
  int clamped = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const int n = 3 + trial % 30;
    const Eigen::MatrixXd g = randomSpd(n, rng);
    Eigen::VectorXd m(n);
    for (int i = 0; i < n; ++i) m[i] = normal(rng);
    const Eigen::VectorXd c = nonNegativeProjection(g, m);
    const Eigen::VectorXd gradient = m - g * c;
    const double scale = 1e-9 * (1.0 + g.cwiseAbs().maxCoeff() * c.cwiseAbs().maxCoeff() + m.cwiseAbs().maxCoeff());
    for (int i = 0; i < n; ++i) {
      ASSERT_GE(c[i], 0.0);
      if (c[i] > 0.0) {
        ASSERT_NEAR(gradient[i], 0.0, scale) << "trial " << trial;
      } else {
        ASSERT_LE(gradient[i], scale) << "trial " << trial;
        ++clamped;
      }
    }
  }
  EXPECT_GT(clamped, 100);  // the constraint was actually exercised
}

// Which bases --non-negative serves: those whose channel-0 functions never go below zero. SH
// bands above 0 change sign, and so do the Bézier patches of ad-rgb and ad-ycocg's Y, whose
// tangent terms dip below zero between vertices.
TEST(NonNegativeFunctions, TellsSignChangingBasesFromNonNegativeOnes) {
  for (const char* name : {"sh-l1", "sh-l2", "sh-l8", "ad-rgb", "ad-rgb-flat", "ad-ycocg"})
    EXPECT_FALSE(functionsAreNonNegative(makeBasis(name)->functions(0))) << name;
  for (const char* name : {"sh-l0", "ad-linear", "ad-cos2", "ad-srbf", "ambient-cube", "sg-6", "sg-12", "sg-64"})
    EXPECT_TRUE(functionsAreNonNegative(makeBasis(name)->functions(0))) << name;
}

}  // namespace
}  // namespace baker
