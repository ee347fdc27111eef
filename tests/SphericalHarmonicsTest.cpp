#include <gtest/gtest.h>

#include <Eigen/Dense>

#include "basis/Quadrature.h"
#include "basis/SphericalHarmonics.h"

namespace baker {
namespace {

TEST(GaussLegendre, IntegratesPolynomialsExactly) {
  std::vector<double> x, w;
  gaussLegendre(7, &x, &w);
  for (int degree = 0; degree <= 13; ++degree) {
    double sum = 0.0;
    for (int i = 0; i < 7; ++i) sum += w[i] * std::pow(x[i], degree);
    const double exact = degree % 2 ? 0.0 : 2.0 / (degree + 1);
    EXPECT_NEAR(sum, exact, 1e-14) << "degree " << degree;
  }
}

TEST(SphericalHarmonics, OrthonormalUpToOrder8) {
  const SphericalHarmonics sh(8);
  // Products of two order-8 harmonics have degree 16: exact with 9 z-nodes and 17+ φ steps.
  const DirectionSet q = gaussProductSphere(12, 24);
  const int n = sh.count();
  Eigen::MatrixXd gram = Eigen::MatrixXd::Zero(n, n);
  Eigen::VectorXd y(n);
  for (std::size_t k = 0; k < q.size(); ++k) {
    sh.evaluate(q.directions[k], y.data());
    gram += q.weights[k] * y * y.transpose();
  }
  EXPECT_LT((gram - Eigen::MatrixXd::Identity(n, n)).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(SphericalHarmonics, MatchesTheReferenceToolsConventionThroughOrder2) {
  const SphericalHarmonics sh(2);
  const Eigen::Vector3d d = Eigen::Vector3d(0.3, -0.5, 0.8).normalized();
  const double x = d.x(), y = d.y(), z = d.z();
  double v[9];
  sh.evaluate(d, v);
  const double c0 = 0.5 / std::sqrt(M_PI), c1 = std::sqrt(3.0 / (4 * M_PI)), c2 = 0.5 * std::sqrt(15.0 / M_PI);
  const double expected[9] = {c0,         c1 * y, c1 * z, c1 * x, c2 * x * y, c2 * y * z,
                              0.25 * std::sqrt(5.0 / M_PI) * (3 * z * z - 1), c2 * x * z,
                              0.5 * c2 * (x * x - y * y)};
  for (int i = 0; i < 9; ++i) EXPECT_NEAR(v[i], expected[i], 1e-14) << "index " << i;
}

}  // namespace
}  // namespace baker
