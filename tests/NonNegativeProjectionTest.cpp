#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

#include "bake/NonNegativeProjection.h"

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

}  // namespace
}  // namespace baker
