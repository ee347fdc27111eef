// Ill-conditioned projections: each is either computed exactly or refused with a message that
// says why; none is baked into coefficients that mean nothing. baker refuses rather than
// regularises (GramOperators).
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <filesystem>

#include "basis/BasisRegistry.h"
#include "basis/GramOperators.h"
#include "basis/ProjectionOperator.h"
#include "basis/SphericalGaussianBasis.h"
#include "basis/SphericalHarmonics.h"
#include "common/Error.h"
#include "scene/RayTracer.h"
#include "tests/GltfTestAssets.h"
#include "tests/TestData.h"
#include "tests/TransportTestSupport.h"

namespace baker {
namespace {

std::string refusalOf(const SphericalFunctions& functions, const std::string& label) {
  try {
    GramOperators ops(functions, label);
  } catch (const NumericalError& e) {
    return e.what();
  }
  return "";
}

// At λ = 1000 an sg-64 lobe is about 2° wide, far narrower than a piece of the exact
// quadrature: its Gram matrix came out 11 % wrong and still well conditioned, so nothing
// noticed. At 1e6 it even looked singular.
TEST(StressConditioning, SgLobesTooSharpToIntegrateAreRefused) {
  for (double sharpness : {1e3, 1e6}) {
    const auto basis = makeBasis("sg-64", {sharpness});
    const std::string message = refusalOf(basis->functions(0), basis->name());
    EXPECT_NE(message.find("too sharp to integrate exactly"), std::string::npos) << message;
    EXPECT_NE(message.find(fmt::format("with sharpness {}", sharpness)), std::string::npos) << message;
    EXPECT_NE(message.find("refuses such a basis rather than regularising it"), std::string::npos) << message;
  }
}

// Broad lobes all look alike: the Gram matrix is singular to working precision.
TEST(StressConditioning, SgLobesTooBroadToTellApartAreRefused) {
  const auto basis = makeBasis("sg-64", {0.1});
  const std::string message = refusalOf(basis->functions(0), basis->name());
  EXPECT_NE(message.find("numerically singular"), std::string::npos) << message;
  EXPECT_NE(message.find("too broad or too alike"), std::string::npos) << message;
}

// Between the two, the quadrature Gram matrix is the closed form's to the promised 1e-9.
TEST(StressConditioning, SgSharpnessesInRangeGiveTheExactGram) {
  for (double sharpness : {SphericalGaussianBasis::defaultSharpness(64), 30.0}) {
    const SphericalGaussianBasis basis(64, sharpness);
    const auto& lobes = static_cast<const SphericalGaussians&>(basis.functions(0));
    const GramOperators ops(lobes, basis.name());
    Eigen::MatrixXd exact(lobes.count(), lobes.count());
    for (int i = 0; i < lobes.count(); ++i)
      for (int j = 0; j < lobes.count(); ++j)
        exact(i, j) = sphericalGaussianInnerProduct(lobes.axes()[i], sharpness, lobes.axes()[j], sharpness);
    EXPECT_LT((ops.gram() - exact).cwiseAbs().maxCoeff(), 1e-9 * exact.cwiseAbs().maxCoeff()) << sharpness;
  }
}

// Two lobes 1e-7 rad apart are one function twice over.
TEST(StressConditioning, NearDuplicateLobesAreRefused) {
  std::vector<Eigen::Vector3d> axes = sphericalFibonacci(8).directions;
  axes.push_back((axes[0] + 1e-7 * axes[0].unitOrthogonal()).normalized());
  const SphericalGaussians lobes(axes, 2.0);
  EXPECT_NE(refusalOf(lobes, "sg-twin").find("numerically singular"), std::string::npos);
}

// Directions bunched within 1e-7 rad of one another cannot pin down nine SH functions; a
// well-spread set with every direction doubled can, and duplicates then change nothing.
TEST(StressConditioning, NearDuplicateSampleDirectionsAreRefusedOnlyWhenTheyCannotResolve) {
  const SphericalHarmonics sh(2);
  DirectionSet bunched;
  const DirectionSet spread = sphericalFibonacci(64);
  for (const Eigen::Vector3d& d : spread.directions) {
    bunched.directions.push_back((Eigen::Vector3d::UnitZ() + 1e-7 * d).normalized());
    bunched.weights.push_back(4.0 * M_PI / 64.0);
  }
  EXPECT_THROW(leastSquaresProjection(sh, bunched, "bunched"), NumericalError);

  DirectionSet doubled;
  for (const Eigen::Vector3d& d : spread.directions)
    for (const Eigen::Vector3d& twin : {d, Eigen::Vector3d((d + 1e-7 * d.unitOrthogonal()).normalized())}) {
      doubled.directions.push_back(twin);
      doubled.weights.push_back(2.0 * M_PI / 64.0);
    }
  const ProjectionOperator fit = leastSquaresProjection(sh, doubled, "doubled");
  EXPECT_LT(fit.conditionNumber, 10.0);
  // Each SH function, sampled at the doubled set, is fitted back to itself.
  for (int f = 0; f < sh.count(); ++f) {
    Eigen::VectorXd samples(doubled.size());
    std::vector<double> y(sh.count());
    for (std::size_t k = 0; k < doubled.size(); ++k) {
      sh.evaluate(doubled.directions[k], y.data());
      samples[k] = y[f];
    }
    const Eigen::VectorXd coefficients = fit.matrix * samples;
    EXPECT_LT((coefficients - Eigen::VectorXd::Unit(sh.count(), f)).cwiseAbs().maxCoeff(), 1e-9) << f;
  }
}

// sh-l8 from a handful of rays: the samples are fitted only up to the order they resolve
// (L with 4(L+1)² ≤ rays), so the fit is never singular and the unresolved bands stay empty.
// A constant sky still comes out exactly: E = π·L for every normal.
TEST(StressConditioning, HighOrderShFromFewRaysKeepsOnlyTheResolvedBands) {
  Scene scene;
  scene.environment = Environment::constant(Eigen::Vector3f(0.5f, 1.0f, 2.0f));
  const RayTracer tracer(scene);
  const auto basis = makeBasis("sh-l8");
  for (int rays : {1, 3, 16, 17, 64}) {
    BakeSettings settings;
    settings.rays = rays;
    const test::BakedProbe probe = test::bakeProbe(scene, tracer, *basis, settings, Eigen::Vector3f::Zero());
    const int resolved = resolvableShOrder(std::size_t(rays));
    for (int c = 0; c < 3; ++c) {
      const float* channel = probe.coefficients.data() + c * 81;
      for (int i = 0; i < 81; ++i) {
        ASSERT_TRUE(std::isfinite(channel[i])) << rays << " rays, coefficient " << i;
        if (i >= (resolved + 1) * (resolved + 1)) EXPECT_LT(std::abs(channel[i]), 1e-6f * std::abs(channel[0])) << i;
      }
    }
    for (const Eigen::Vector3d& n : sphericalFibonacci(32).directions) {
      const Eigen::Vector3f e = basis->reconstruct(probe.coefficients.data(), n);
      EXPECT_LT((e - float(M_PI) * scene.environment.constantRadiance()).cwiseAbs().maxCoeff(), 1e-4f) << rays;
    }
  }
  // Asked for directly, order 8 from 16 directions is refused.
  EXPECT_THROW(leastSquaresProjection(SphericalHarmonics(8), sphericalFibonacci(16), "sh-l8"), NumericalError);
}

// The command line turns the refusal into one line and exit code 2, with nothing written.
TEST(StressConditioning, TheBakeCommandRefusesAnUnresolvableSharpness) {
  const std::string dir = test::makeTempDir("stress-sg-sharpness");
  const test::ProcessResult run = test::runBaker(
      dir, "'" + test::sourcePath("data/default_room/default_room.gltf") +
               "' --basis sg-64 --sg-sharpness 1000 --rays 16 --out out.vdb --quiet");
  EXPECT_EQ(run.exitCode, 2) << run.err;
  EXPECT_NE(run.err.find("too sharp to integrate exactly"), std::string::npos) << run.err;
  EXPECT_FALSE(std::filesystem::exists(dir + "/out.vdb"));
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace baker
