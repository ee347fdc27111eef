#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "basis/BasisRegistry.h"
#include "basis/DirectionSet.h"
#include "basis/ProjectionOperator.h"
#include "basis/Quadrature.h"
#include "basis/SphericalGaussianBasis.h"
#include "common/Error.h"

namespace baker {
namespace {

TEST(SphericalGaussians, NamesAcceptEveryCountFrom1To64) {
  EXPECT_EQ(sphericalGaussianLobeCount("sg-1"), 1);
  EXPECT_EQ(sphericalGaussianLobeCount("sg-12"), 12);
  EXPECT_EQ(sphericalGaussianLobeCount("sg-64"), 64);
  for (const char* bad : {"sg-", "sg-0", "sg-65", "sg-012", "sg-1x", "sg-100", "sg12", "xsg-12"})
    EXPECT_EQ(sphericalGaussianLobeCount(bad), 0) << bad;

  const auto basis = makeBasis("sg-12");
  EXPECT_EQ(basis->name(), "sg-12");
  EXPECT_EQ(basis->totalCoefficients(), 36);
  EXPECT_EQ(basis->coefficientsPerLookup(), 36);
  EXPECT_THROW(makeBasis("sg-65"), InputError);
  EXPECT_THROW(makeBasis("sg-0"), InputError);
}

TEST(SphericalGaussians, DefaultSharpnessFollowsTheMeasuredTable) {
  EXPECT_EQ(SphericalGaussianBasis::defaultSharpness(9), 0.209);
  EXPECT_EQ(SphericalGaussianBasis::defaultSharpness(32), 2.49);
  EXPECT_DOUBLE_EQ(SphericalGaussianBasis::defaultSharpness(3), 0.278 / 2);  // λ ∝ N below the table
  // Between measured counts: geometric interpolation, so strictly between the neighbours.
  const double ten = SphericalGaussianBasis::defaultSharpness(10);
  EXPECT_GT(ten, 0.209);
  EXPECT_LT(ten, 0.542);
  for (int n = 1; n <= SphericalGaussianBasis::kMaxLobes; ++n) {
    const double sharpness = SphericalGaussianBasis::defaultSharpness(n);
    EXPECT_TRUE(sharpness > 0.0 && std::isfinite(sharpness)) << n;
  }
  EXPECT_EQ(SphericalGaussianBasis(9).sharpness(), 0.209);
  EXPECT_EQ(SphericalGaussianBasis(9, 2.5).sharpness(), 2.5);
}

// Thesis eq. 2.11 against a Gauss product rule, which converges exponentially for these
// entire functions: exp(λ1 μ1·d + λ2 μ2·d) needs degree ~ λ1 + λ2 + 60 for 1e-16.
TEST(SphericalGaussians, ClosedFormInnerProductMatchesQuadrature) {
  const DirectionSet quadrature = gaussProductSphere(96, 192);
  const auto integrate = [&](const Eigen::Vector3d& a, double la, const Eigen::Vector3d& b, double lb) {
    double sum = 0.0;
    for (std::size_t k = 0; k < quadrature.size(); ++k) {
      const Eigen::Vector3d& d = quadrature.directions[k];
      sum += quadrature.weights[k] * std::exp(la * (a.dot(d) - 1.0) + lb * (b.dot(d) - 1.0));
    }
    return sum;
  };
  // Every pair of the default sg-12 set, including each lobe with itself.
  const SphericalGaussianBasis basis(12);
  const auto& gaussians = static_cast<const SphericalGaussians&>(basis.functions(0));
  for (int i = 0; i < 12; ++i)
    for (int j = i; j < 12; ++j) {
      const Eigen::Vector3d &a = gaussians.axes()[i], &b = gaussians.axes()[j];
      const double lambda = gaussians.sharpness();
      const double closed = sphericalGaussianInnerProduct(a, lambda, b, lambda);
      EXPECT_NEAR(closed, integrate(a, lambda, b, lambda), 1e-10 * closed) << i << ", " << j;
    }
  // Unequal sharpness, random axes, and exactly opposite equal lobes (r = 0).
  std::mt19937 rng(17);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> sharpness(0.1, 30.0);
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::Vector3d a = Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized();
    const Eigen::Vector3d b = Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized();
    const double la = sharpness(rng), lb = sharpness(rng);
    const double closed = sphericalGaussianInnerProduct(a, la, b, lb);
    EXPECT_NEAR(closed, integrate(a, la, b, lb), 1e-10 * closed) << trial;
  }
  const Eigen::Vector3d z = Eigen::Vector3d::UnitZ();
  EXPECT_NEAR(sphericalGaussianInnerProduct(z, 3.0, -z, 3.0), integrate(z, 3.0, -z, 3.0),
              1e-10 * integrate(z, 3.0, -z, 3.0));
}

TEST(SphericalGaussians, LeastSquaresReproducesAFunctionInTheSpan) {
  const SphericalGaussianBasis basis(9);
  const SphericalFunctions& lobes = basis.functions(0);
  const DirectionSet dirs = sphericalFibonacci(512);
  const ProjectionOperator op = leastSquaresProjection(lobes, dirs, basis.name());
  std::mt19937 rng(23);
  std::normal_distribution<double> normal;
  for (int trial = 0; trial < 5; ++trial) {
    Eigen::VectorXd c(9), samples(dirs.size()), values(9);
    for (int i = 0; i < 9; ++i) c[i] = normal(rng);
    for (std::size_t k = 0; k < dirs.size(); ++k) {
      lobes.evaluate(dirs.directions[k], values.data());
      samples[k] = values.dot(c);
    }
    EXPECT_LT((op.matrix * samples - c).cwiseAbs().maxCoeff(), 1e-9 * c.cwiseAbs().maxCoeff());
  }
}

TEST(SphericalGaussians, FastLookupMatchesEvaluatingEveryChannel) {
  const SphericalGaussianBasis basis(16);
  std::mt19937 rng(29);
  std::uniform_real_distribution<float> uniform(-1.0f, 1.0f);
  std::vector<float> coefficients(48);
  for (float& c : coefficients) c = uniform(rng);
  for (const Eigen::Vector3d& d : sphericalFibonacci(200).directions) {
    const Eigen::Vector3f expected = basis.Basis::reconstruct(coefficients.data(), d);
    EXPECT_LT((basis.reconstruct(coefficients.data(), d) - expected).cwiseAbs().maxCoeff(), 1e-6f);
  }
}

}  // namespace
}  // namespace baker
