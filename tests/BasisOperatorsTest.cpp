#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <random>

#include "basis/BasisRegistry.h"
#include "basis/GramOperators.h"
#include "basis/SphereQuadrature.h"
#include "basis/SphericalHarmonics.h"
#include "tests/OnThreads.h"

namespace baker {
namespace {

// Every distinct function set of every registered basis, with the basis kept alive.
struct FunctionSet {
  std::string label;
  std::shared_ptr<Basis> basis;
  int channel;
  const SphericalFunctions& functions() const { return basis->functions(channel); }
};

std::vector<FunctionSet> allFunctionSets() {
  std::vector<FunctionSet> sets;
  for (const std::string& name : basisNames()) {
    std::shared_ptr<Basis> basis = makeBasis(name);
    for (int c = 0; c < 3; ++c)
      if (c == 0 || &basis->functions(c) != &basis->functions(c - 1))
        sets.push_back({name + "/" + channelName(basis->colorSpace(), c), basis, c});
  }
  return sets;
}

TEST(BasisOperators, GramIsSymmetricPositiveDefiniteAndConverged) {
  for (const FunctionSet& set : allFunctionSets()) {
    const Eigen::MatrixXd g = innerProducts(set.functions(), set.functions());
    const Eigen::MatrixXd finer = innerProducts(set.functions(), set.functions(), kExactQuadratureOrder + 8);
    EXPECT_LT((g - g.transpose()).cwiseAbs().maxCoeff(), 1e-14 * g.cwiseAbs().maxCoeff()) << set.label;
    EXPECT_GT(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(g).eigenvalues().minCoeff(), 0.0) << set.label;
    // The bar: Gram entries accurate to 1e-9 relative.
    EXPECT_LT((g - finer).cwiseAbs().maxCoeff(), 1e-9 * g.cwiseAbs().maxCoeff()) << set.label;
  }
}

// Any function in the span comes back exactly from its samples at the exact quadrature.
TEST(BasisOperators, ProjectionFromSamplesReproducesTheSpan) {
  std::mt19937 rng(11);
  std::normal_distribution<double> normal;
  for (const FunctionSet& set : allFunctionSets()) {
    const SphericalFunctions& f = set.functions();
    const GramOperators ops(f, set.label);
    std::vector<Eigen::Vector3d> kinks = f.kinkPlanes();
    const DirectionSet q = piecewiseSphereQuadrature(kExactQuadratureOrder, kinks);
    Eigen::VectorXd c(f.count()), values(f.count()), samples(q.size());
    for (int i = 0; i < f.count(); ++i) c[i] = normal(rng);
    for (std::size_t k = 0; k < q.size(); ++k) {
      f.evaluate(q.directions[k], values.data());
      samples[k] = values.dot(c);
    }
    EXPECT_LT((ops.fromSamples(q) * samples - c).cwiseAbs().maxCoeff(), 1e-8 * c.cwiseAbs().maxCoeff()) << set.label;
  }
}

// The bands the clamped cosine (and the window) multiply by zero are never integrated: the
// operator must still be G⁻¹ B_sh C over all bands, with exactly zero columns for those bands.
TEST(BasisOperators, IrradianceFromShLeavesOutOnlyTheBandsItZeroes) {
  constexpr int kOrder = 8;
  for (const FunctionSet& set : allFunctionSets()) {
    const GramOperators ops(set.functions(), set.label);
    for (const BandWindow window : {BandWindow{}, BandWindow{5}}) {
      Eigen::VectorXd factors(SphericalHarmonics(kOrder).count());
      for (int l = 0; l <= kOrder; ++l)
        factors.segment(l * l, 2 * l + 1).setConstant(clampedCosineBand(l) * window.factor(l));
      const Eigen::MatrixXd full = ops.gramInverse() * ops.shMoments(kOrder) * factors.asDiagonal();
      const Eigen::MatrixXd kept = ops.irradianceFromSh(kOrder, window);
      ASSERT_EQ(kept.cols(), full.cols());
      EXPECT_LT((kept - full).cwiseAbs().maxCoeff(), 1e-12 * full.cwiseAbs().maxCoeff())
          << set.label << ", window " << window.hannWidth;
      for (int j = 0; j < factors.size(); ++j)
        if (factors[j] == 0.0) EXPECT_TRUE((kept.col(j).array() == 0.0).all()) << set.label << ", column " << j;
    }
  }
}

// An SH basis's operators from SH are diagonal in exact arithmetic; the quadrature leaves
// ±1e-17 off the diagonal, which would reach every probe as coefficients of rounding noise
// (sky visibility's band 2 at 16 rays, fitted to band 1 only). They must be exact zeros.
TEST(BasisOperators, ShBasisOperatorsHoldExactZerosOffTheDiagonal) {
  const auto basis = makeBasis("sh-l2");
  const GramOperators ops(basis->functions(0), "sh-l2");
  for (const Eigen::MatrixXd& op : {ops.irradianceFromSh(1), ops.irradianceFromSh(4), ops.radianceToIrradiance()}) {
    for (Eigen::Index i = 0; i < op.rows(); ++i)
      for (Eigen::Index j = 0; j < op.cols(); ++j)
        if (i != j) EXPECT_EQ(op(i, j), 0.0) << "entry (" << i << ", " << j << ") of a " << op.rows() << " × " << op.cols();
    const int l = 1;
    EXPECT_NEAR(op(l * l, l * l), clampedCosineBand(l), 1e-12);
  }
}

// Inner products are summed in chunks fixed by the quadrature, not by the threads, and each
// block multiplies only the functions non-zero on it: the same bits on one thread and on
// three, and the plain sum over every node, for f against SH and for f against itself (Gram).
TEST(BasisOperators, InnerProductsAreTheSameOnAnyNumberOfThreadsAndMatchThePlainSum) {
  const auto basis = makeBasis("ad-ycocg");
  const SphericalFunctions& f = basis->functions(0);
  const SphericalHarmonics sh(6);
  const Eigen::MatrixXd moments = test::onThreads(1, [&] { return innerProducts(f, sh); });
  const Eigen::MatrixXd gram = test::onThreads(1, [&] { return innerProducts(f, f); });
  EXPECT_TRUE(test::onThreads(3, [&] { return innerProducts(f, sh); }) == moments);
  EXPECT_TRUE(test::onThreads(3, [&] { return innerProducts(f, f); }) == gram);

  const DirectionSet q = piecewiseSphereQuadrature(kExactQuadratureOrder, f.kinkPlanes());
  Eigen::MatrixXd plainMoments = Eigen::MatrixXd::Zero(f.count(), sh.count());
  Eigen::MatrixXd plainGram = Eigen::MatrixXd::Zero(f.count(), f.count());
  Eigen::VectorXd fValues(f.count()), shValues(sh.count());
  for (std::size_t k = 0; k < q.size(); ++k) {
    f.evaluate(q.directions[k], fValues.data());
    sh.evaluate(q.directions[k], shValues.data());
    plainMoments += q.weights[k] * fValues * shValues.transpose();
    plainGram += q.weights[k] * fValues * fValues.transpose();
  }
  EXPECT_LT((moments - plainMoments).cwiseAbs().maxCoeff(), 1e-12 * plainMoments.cwiseAbs().maxCoeff());
  EXPECT_LT((gram - plainGram).cwiseAbs().maxCoeff(), 1e-12 * plainGram.cwiseAbs().maxCoeff());
}

// A constant radiance of 1 gives an irradiance of π for every normal (paper eq. 7). The
// bases that reproduce constants must say so through their operator.
TEST(BasisOperators, IrradianceOperatorMapsUnitRadianceToPi) {
  for (const char* name : {"ad-linear", "ad-rgb-flat", "sh-l2"}) {
    const auto basis = makeBasis(name);
    const SphericalFunctions& f = basis->functions(0);
    const GramOperators ops(f, name);
    const Eigen::VectorXd one = ops.fromSh(0).col(0) * std::sqrt(4 * M_PI);  // Y00 · √(4π) = 1
    int order = 0;
    const Eigen::VectorXd irradiance = ops.radianceToIrradiance({}, &order) * one;
    EXPECT_LT((irradiance - M_PI * one).cwiseAbs().maxCoeff(), 1e-5) << name << " at SH order " << order;
  }
}

// Windowing (paper eq. 8) scales band l by the window: on SH it is diag(A_l·h_l).
TEST(BasisOperators, WindowScalesEachBand) {
  const auto basis = makeBasis("sh-l4");
  const GramOperators ops(basis->functions(0), "sh-l4");
  const BandWindow window{3};
  const Eigen::MatrixXd op = ops.radianceToIrradiance(window);
  for (int l = 0; l <= 4; ++l)
    for (int m = -l; m <= l; ++m) {
      const int i = l * l + l + m;
      EXPECT_NEAR(op(i, i), clampedCosineBand(l) * window.factor(l), 1e-12) << "l=" << l;
    }
  EXPECT_EQ(window.factor(4), 0.0);
  EXPECT_EQ(window.factor(0), 1.0);
}

}  // namespace
}  // namespace baker
