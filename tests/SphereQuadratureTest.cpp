#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <Eigen/Dense>

#include "basis/GramOperators.h"
#include "basis/SphereQuadrature.h"
#include "basis/SphericalHarmonics.h"

namespace baker {
namespace {

// Clamped lobes max(0, v·d)^p at a few fixed directions: kinks that cut the icosahedral tiling
// at arbitrary angles, like the Ambient Dice SRBF lobes do.
class ClampedLobes : public SphericalFunctions {
 public:
  ClampedLobes(int power, bool declareKinks) : power_(power), declareKinks_(declareKinks) {
    axes_ = {Eigen::Vector3d(0.3, 0.8, -0.5).normalized(), Eigen::Vector3d(-0.9, 0.1, 0.4).normalized(),
             Eigen::Vector3d(0.2, -0.7, -0.6).normalized()};
  }
  int count() const override { return int(axes_.size()); }
  void evaluate(const Eigen::Vector3d& d, double* values) const override {
    for (std::size_t i = 0; i < axes_.size(); ++i) values[i] = std::pow(std::max(0.0, axes_[i].dot(d)), power_);
  }
  std::vector<Eigen::Vector3d> kinkPlanes() const override {
    return declareKinks_ ? axes_ : std::vector<Eigen::Vector3d>{};
  }

 private:
  int power_;
  bool declareKinks_;
  std::vector<Eigen::Vector3d> axes_;
};

double integrate(const DirectionSet& q, const std::function<double(const Eigen::Vector3d&)>& f) {
  double sum = 0.0;
  for (std::size_t k = 0; k < q.size(); ++k) sum += q.weights[k] * f(q.directions[k]);
  return sum;
}

// The gnomonic Jacobian is rational, not polynomial, so even a constant needs a few orders.
TEST(SphereQuadrature, MeasuresTheWholeSphere) {
  auto area = [](int order) { return integrate(piecewiseSphereQuadrature(order), [](auto&) { return 1.0; }); };
  EXPECT_NEAR(area(4), 4 * M_PI, 1e-4);
  EXPECT_NEAR(area(8), 4 * M_PI, 1e-9);
  EXPECT_NEAR(area(kExactQuadratureOrder), 4 * M_PI, 1e-12);
}

// Products of order-16 harmonics are degree-32 polynomials, well beyond any basis's Gram.
TEST(SphereQuadrature, IntegratesHarmonicsToOrder16) {
  const SphericalHarmonics sh(16);
  const Eigen::MatrixXd gram = innerProducts(sh, sh);
  EXPECT_LT((gram - Eigen::MatrixXd::Identity(gram.rows(), gram.cols())).cwiseAbs().maxCoeff(), 1e-10);
}

// ∫ max(0, v·d)^p dω = 2π/(p+1): the clamped lobe alone, and its Gram diagonal (power 2p).
TEST(SphereQuadrature, ClampedLobesAreExactWhenTheirKinksAreDeclared) {
  const ClampedLobes lobes(2, true);
  const Eigen::MatrixXd gram = innerProducts(lobes, lobes);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(gram(i, i), 2 * M_PI / 5, 1e-13);
}

// Convergence in the order: with declared kinks the Gram stops changing at rounding level by
// order 16; without them it is stuck near 1e-5, which is why bases declare their kinks.
TEST(SphereQuadrature, ConvergesExponentiallyOnPiecewiseSmoothFunctions) {
  const ClampedLobes declared(2, true), undeclared(2, false);
  const Eigen::MatrixXd reference = innerProducts(declared, declared, 32);
  double previousError = 1.0;
  for (int order : {2, 4, 8, 16}) {
    const double error = (innerProducts(declared, declared, order) - reference).cwiseAbs().maxCoeff();
    EXPECT_LT(error, previousError) << "order " << order;
    previousError = error;
  }
  EXPECT_LT(previousError, 1e-12 * reference.maxCoeff());
  const double undeclaredError = (innerProducts(undeclared, undeclared, 16) - reference).cwiseAbs().maxCoeff();
  EXPECT_GT(undeclaredError, 1e-9);
}

// The sum that does not hold the rule: clamped lobes' integrals 2π/(p+1) for p = 2 and 4, with
// their kinks cut, and the stored rule's sums to their rounding (summed in another order); the
// same bits at any thread count.
TEST(SphereQuadrature, SumsPieceByPieceAsTheStoredRuleDoes) {
  const ClampedLobes lobes(2, true);
  const auto lobeIntegrals = [&](const DirectionSet& nodes, Eigen::VectorXd* sum) {
    double values[3];
    for (std::size_t k = 0; k < nodes.size(); ++k) {
      lobes.evaluate(nodes.directions[k], values);
      for (int i = 0; i < 3; ++i) {
        (*sum)[i] += nodes.weights[k] * values[i];
        (*sum)[3 + i] += nodes.weights[k] * values[i] * values[i];
      }
    }
  };
  const Eigen::VectorXd sums = sumOverSphereQuadrature(kExactQuadratureOrder, lobes.kinkPlanes(), 6, lobeIntegrals);
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(sums[i], 2 * M_PI / 3, 1e-13);
    EXPECT_NEAR(sums[3 + i], 2 * M_PI / 5, 1e-13);
  }
  const DirectionSet stored = piecewiseSphereQuadrature(kExactQuadratureOrder, lobes.kinkPlanes());
  Eigen::VectorXd storedSums = Eigen::VectorXd::Zero(6);
  lobeIntegrals(stored, &storedSums);
  EXPECT_LT((sums - storedSums).cwiseAbs().maxCoeff(), 1e-13);

  // Filled and summed in parallel, both give the same bits on one thread.
  const tbb::global_control oneThread(tbb::global_control::max_allowed_parallelism, 1);
  const DirectionSet storedAlone = piecewiseSphereQuadrature(kExactQuadratureOrder, lobes.kinkPlanes());
  EXPECT_TRUE(storedAlone.directions == stored.directions);
  EXPECT_TRUE(storedAlone.weights == stored.weights);
  const Eigen::VectorXd sumsAlone =
      sumOverSphereQuadrature(kExactQuadratureOrder, lobes.kinkPlanes(), 6, lobeIntegrals);
  EXPECT_TRUE(sumsAlone == sums);
}

TEST(GramOperators, ClampedCosineBandsMatchTheKnownValues) {
  EXPECT_DOUBLE_EQ(clampedCosineBand(0), M_PI);
  EXPECT_DOUBLE_EQ(clampedCosineBand(1), 2 * M_PI / 3);
  EXPECT_NEAR(clampedCosineBand(2), M_PI / 4, 1e-15);
  EXPECT_EQ(clampedCosineBand(3), 0.0);
  EXPECT_NEAR(clampedCosineBand(4), -M_PI / 24, 1e-15);
  EXPECT_NEAR(clampedCosineBand(6), M_PI / 64, 1e-15);
}

// For orthonormal SH the Gram is the identity and eq. 7 reduces to diag(A_l).
TEST(GramOperators, ShIrradianceOperatorIsTheDiagonalOfBands) {
  const SphericalHarmonics sh(3);
  const GramOperators ops(sh, "sh-l3");
  EXPECT_LT(ops.conditionNumber(), 1.0 + 1e-10);
  const Eigen::MatrixXd op = ops.radianceToIrradiance();
  Eigen::VectorXd expected(16);
  for (int l = 0; l <= 3; ++l)
    for (int m = -l; m <= l; ++m) expected[l * l + l + m] = clampedCosineBand(l);
  EXPECT_LT((op - Eigen::MatrixXd(expected.asDiagonal())).cwiseAbs().maxCoeff(), 1e-12);
  const ShReproduction r = ops.shReproduction(4);
  EXPECT_LT(r.cumulative[3], 1e-12);  // SH reproduces itself
  EXPECT_NEAR(r.cumulative[4], 3.0, 1e-12);  // and none of band 4: ‖I₉‖ = 3
}

TEST(GramOperators, RefusesASingularGram) {
  Eigen::MatrixXd singular = Eigen::MatrixXd::Identity(3, 3);
  singular(2, 2) = 1e-15;
  double condition = 0.0;
  EXPECT_THROW(invertSymmetric(singular, "test", &condition), std::exception);
  EXPECT_GT(condition, 1e14);
}

}  // namespace
}  // namespace baker
