#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "basis/AmbientDiceBezier.h"
#include "basis/AmbientDiceLinear.h"
#include "basis/AmbientDiceSrbf.h"
#include "basis/BasisRegistry.h"
#include "basis/Icosahedron.h"
#include "tests/RandomDirection.h"

namespace baker {
namespace {

const Icosahedron& ico() { return Icosahedron::instance(); }

const char* const kNames[] = {"ad-linear", "ad-cos2", "ad-srbf", "ad-rgb", "ad-rgb-flat", "ad-ycocg"};

using test::randomDirection;

Eigen::VectorXd randomData(int n, std::mt19937_64& rng) {
  std::normal_distribution<double> normal;
  Eigen::VectorXd data(n);
  for (int i = 0; i < n; ++i) data[i] = normal(rng);
  return data;
}

// Σ data_i f_i(d): one function of the span.
double combination(const SphericalFunctions& f, const Eigen::VectorXd& data, const Eigen::Vector3d& d) {
  Eigen::VectorXd values(f.count());
  f.evaluate(d, values.data());
  return values.dot(data);
}

// The point at angle s along the great circle leaving unit p in the unit tangent direction u.
Eigen::Vector3d walk(const Eigen::Vector3d& p, const Eigen::Vector3d& u, double s) {
  return std::cos(s) * p + std::sin(s) * u;
}

// The derivative at p along u from the side u points into: a one-sided second-order
// difference, so it never straddles an edge; its error is about h²/3 times the third derivative.
double derivativeAlong(const SphericalFunctions& f, const Eigen::VectorXd& data, const Eigen::Vector3d& p,
                       const Eigen::Vector3d& u, double h) {
  return (-3.0 * combination(f, data, p) + 4.0 * combination(f, data, walk(p, u, h)) -
          combination(f, data, walk(p, u, 2.0 * h))) /
         (2.0 * h);
}

struct Edge {
  Eigen::Vector3d a, b, normal;  // normal = a × b normalised: points to one side of the edge
  Eigen::Vector3d at(double fraction) const {
    return walk(a, normal.cross(a), fraction * std::acos(a.dot(b)));
  }
};

std::vector<Edge> edges() {
  std::vector<Edge> result;
  for (int t = 0; t < Icosahedron::kTriangleCount; ++t)
    for (int k = 0; k < 3; ++k) {
      const int i = ico().triangle(t)[k], j = ico().triangle(t)[(k + 1) % 3];
      if (i < j) result.push_back({ico().vertex(i), ico().vertex(j), ico().vertex(i).cross(ico().vertex(j)).normalized()});
    }
  return result;
}

// Directions where the fast paths are most likely to disagree with the dense evaluation:
// random ones plus vertices, edge points and face centres.
std::vector<Eigen::Vector3d> testDirections(std::mt19937_64& rng, int randomCount) {
  std::vector<Eigen::Vector3d> directions;
  for (int k = 0; k < randomCount; ++k) directions.push_back(randomDirection(rng));
  for (int i = 0; i < 12; ++i) directions.push_back(ico().vertex(i));
  for (const Edge& e : edges())
    for (double fraction : {0.25, 0.5}) directions.push_back(e.at(fraction));
  for (int t = 0; t < 20; ++t) {
    const std::array<int, 3>& tri = ico().triangle(t);
    directions.push_back((ico().vertex(tri[0]) + ico().vertex(tri[1]) + ico().vertex(tri[2])).normalized());
  }
  return directions;
}

TEST(AmbientDice, RegisteredWithTheDocumentedCounts) {
  struct Expected {
    const char* name;
    int total, perLookup;
    bool shared;
  };
  const Expected expected[] = {{"ad-linear", 36, 9, true},  {"ad-cos2", 36, 18, true},     {"ad-srbf", 36, 18, true},
                               {"ad-rgb", 108, 27, true},   {"ad-rgb-flat", 108, 27, true}, {"ad-ycocg", 60, 15, false}};
  const std::vector<std::string> names = basisNames();
  for (const Expected& e : expected) {
    SCOPED_TRACE(e.name);
    EXPECT_NE(std::find(names.begin(), names.end(), e.name), names.end());
    const std::unique_ptr<Basis> basis = makeBasis(e.name);
    EXPECT_EQ(basis->name(), e.name);
    EXPECT_EQ(basis->totalCoefficients(), e.total);
    EXPECT_EQ(basis->coefficientsPerLookup(), e.perLookup);
    EXPECT_EQ(basis->channelsShareFunctions(), e.shared);
    EXPECT_EQ(basis->colorSpace(), e.shared ? ColorSpace::Rgb : ColorSpace::YCoCg);
  }
  const std::unique_ptr<Basis> ycocg = makeBasis("ad-ycocg");
  EXPECT_EQ(ycocg->coefficientCount(0), 36);
  EXPECT_EQ(ycocg->coefficientCount(1), 12);
  EXPECT_EQ(&ycocg->functions(1), &ycocg->functions(2)) << "Co and Cg must share functions to be projected together";
}

TEST(AmbientDice, FastReconstructionMatchesDenseEvaluation) {
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<float> uniform(-1.0f, 1.0f);
  const std::vector<Eigen::Vector3d> directions = testDirections(rng, 2000);
  for (const char* name : kNames) {
    SCOPED_TRACE(name);
    const std::unique_ptr<Basis> basis = makeBasis(name);
    for (int probe = 0; probe < 10; ++probe) {
      std::vector<float> coefficients(basis->totalCoefficients());
      for (float& c : coefficients) c = uniform(rng);
      double worst = 0.0;
      for (const Eigen::Vector3d& d : directions) {
        const Eigen::Vector3f fast = basis->reconstruct(coefficients.data(), d);
        const Eigen::Vector3f dense = basis->Basis::reconstruct(coefficients.data(), d);
        worst = std::max(worst, double((fast - dense).cwiseAbs().maxCoeff() / (1.0f + dense.cwiseAbs().maxCoeff())));
      }
      EXPECT_LT(worst, 1e-5) << "probe " << probe;
    }
  }
}

// At a direction inside a triangle (and off every lobe's kink plane) exactly
// coefficientsPerLookup() functions are non-zero; the fast path must not read any other
// coefficient, which here are all NaN.
TEST(AmbientDice, ReconstructionReadsOnlyTheCoefficientsItNeeds) {
  std::mt19937_64 rng(2);
  std::uniform_real_distribution<float> uniform(-1.0f, 1.0f);
  for (const char* name : kNames) {
    SCOPED_TRACE(name);
    const std::unique_ptr<Basis> basis = makeBasis(name);
    for (int trial = 0; trial < 200; ++trial) {
      const Eigen::Vector3d d = randomDirection(rng);
      std::vector<float> coefficients(basis->totalCoefficients());
      for (float& c : coefficients) c = uniform(rng);
      std::vector<float> poisoned(coefficients.size(), std::numeric_limits<float>::quiet_NaN());
      int used = 0;
      for (int c = 0; c < 3; ++c) {
        std::vector<double> values(basis->coefficientCount(c));
        basis->functions(c).evaluate(d, values.data());
        for (int i = 0; i < basis->coefficientCount(c); ++i)
          if (values[i] != 0.0) {
            ++used;
            poisoned[basis->coefficientOffset(c) + i] = coefficients[basis->coefficientOffset(c) + i];
          }
      }
      ASSERT_EQ(used, basis->coefficientsPerLookup());
      const Eigen::Vector3f fast = basis->reconstruct(poisoned.data(), d);
      const Eigen::Vector3f dense = basis->Basis::reconstruct(coefficients.data(), d);
      ASSERT_TRUE(fast.allFinite()) << "read a coefficient it does not need at " << d.transpose();
      EXPECT_LT((fast - dense).cwiseAbs().maxCoeff(), 1e-5f * (1.0f + dense.cwiseAbs().maxCoeff()));
    }
  }
}

TEST(AmbientDiceSrbf, LobesArePartitionsOfUnity) {
  const AmbientDiceSrbfFunctions cos2(1.0, 0.0), cos4(0.0, 1.0), paper(0.7, 0.3);
  // The normalisations the partition forces: ½cos², ⅚cos⁴, and the paper's mix of the raw powers.
  for (double c : {0.0, 0.3, 0.7, 1.0}) {
    EXPECT_NEAR(cos2.lobe(c), 0.5 * c * c, 1e-15);
    EXPECT_NEAR(cos4.lobe(c), 5.0 / 6.0 * std::pow(c, 4), 1e-15);
    EXPECT_NEAR(paper.lobe(c), 35.0 / 44.0 * cos2.lobe(c) + 9.0 / 44.0 * cos4.lobe(c), 1e-15);
    EXPECT_NEAR(paper.lobe(c) * 1.76, 0.7 * c * c + 0.3 * std::pow(c, 4), 1e-15);
  }
  std::mt19937_64 rng(3);
  const std::vector<Eigen::Vector3d> directions = testDirections(rng, 100000);
  for (const AmbientDiceSrbfFunctions* f : {&cos2, &cos4, &paper}) {
    double worst = 0.0;
    for (const Eigen::Vector3d& d : directions) {
      double values[12];
      f->evaluate(d, values);
      double sum = 0.0;
      for (double v : values) sum += v;
      worst = std::max(worst, std::abs(sum - 1.0));
    }
    EXPECT_LT(worst, 1e-12);
  }
}

TEST(AmbientDice, OnlyTheLobesDeclareKinkPlanes) {
  const std::vector<Eigen::Vector3d> planes = AmbientDiceSrbfFunctions(0.7, 0.3).kinkPlanes();
  ASSERT_EQ(planes.size(), 6u);
  for (int i = 0; i < 12; ++i) {
    int matches = 0;  // every lobe kinks on exactly one plane: ±its own vertex
    for (const Eigen::Vector3d& n : planes) matches += std::abs(std::abs(n.dot(ico().vertex(i))) - 1.0) < 1e-15;
    EXPECT_EQ(matches, 1) << "vertex " << i;
  }
  // Linear and Bézier pieces meet on icosahedron edges, which lie on its mirror planes.
  EXPECT_TRUE(AmbientDiceLinearFunctions(Barycentrics::Flat).kinkPlanes().empty());
  EXPECT_TRUE(AmbientDiceLinearFunctions(Barycentrics::Spherical).kinkPlanes().empty());
  EXPECT_TRUE(AmbientDiceBezierFunctions(Barycentrics::Flat).kinkPlanes().empty());
  EXPECT_TRUE(AmbientDiceBezierFunctions(Barycentrics::Spherical).kinkPlanes().empty());
}

// All vertex values 1 and all derivatives 0.
double bezierOfOnes(const AmbientDiceBezierFunctions& f, const Eigen::Vector3d& d) {
  Eigen::VectorXd data = Eigen::VectorXd::Zero(36);
  for (int i = 0; i < 12; ++i) data[3 * i] = 1.0;
  return combination(f, data, d);
}

TEST(AmbientDice, FlatInterpolantsReproduceConstants) {
  const AmbientDiceLinearFunctions linear(Barycentrics::Flat);
  const AmbientDiceBezierFunctions bezier(Barycentrics::Flat);
  std::mt19937_64 rng(4);
  for (const Eigen::Vector3d& d : testDirections(rng, 20000)) {
    EXPECT_NEAR(combination(linear, Eigen::VectorXd::Ones(12), d), 1.0, 1e-12) << d.transpose();
    EXPECT_NEAR(bezierOfOnes(bezier, d), 1.0, 1e-12) << d.transpose();
  }
}

// Cubics in spherical barycentrics cannot be constant on the sphere: with constant data the
// patch is exact at vertices only. At a face centre (b = s(1,1,1), s = 1/√(3 + 6/√5)) every
// edge point is vf = 1/√5 and c111 = 2a0 + 2vf(a1 + a2) = (5 − √5)/10, so the patch is
// s³(3 + 18/√5 + 6(5 − √5)/10) = 0.9380; at an edge midpoint (b = u(1,1,0), u = 1/√(2 + 2/√5))
// it is u³(2 + 6/√5) = 0.9511.
TEST(AmbientDiceBezier, SphericalPatchDoesNotReproduceConstants) {
  const AmbientDiceBezierFunctions bezier(Barycentrics::Spherical);
  const double root5 = std::sqrt(5.0);
  const double s = 1.0 / std::sqrt(3.0 + 6.0 / root5);
  const double atCentre = s * s * s * (3.0 + 18.0 / root5 + 6.0 * (5.0 - root5) / 10.0);
  const double u = 1.0 / std::sqrt(2.0 + 2.0 / root5);
  const double atMidpoint = u * u * u * (2.0 + 6.0 / root5);
  EXPECT_GT(1.0 - atCentre, 0.06);
  EXPECT_GT(1.0 - atMidpoint, 0.04);
  for (int t = 0; t < 20; ++t) {
    const std::array<int, 3>& tri = ico().triangle(t);
    const Eigen::Vector3d centre = (ico().vertex(tri[0]) + ico().vertex(tri[1]) + ico().vertex(tri[2])).normalized();
    EXPECT_NEAR(bezierOfOnes(bezier, centre), atCentre, 1e-12) << "triangle " << t;
  }
  for (const Edge& e : edges()) EXPECT_NEAR(bezierOfOnes(bezier, e.at(0.5)), atMidpoint, 1e-12);
  for (int i = 0; i < 12; ++i) EXPECT_NEAR(bezierOfOnes(bezier, ico().vertex(i)), 1.0, 1e-12);
}

// The unit tangent at a corner along an edge has the same spherical barycentrics in every
// triangle, (−½, √5/2, 0) (corner, far end, other corner). The paper's (β, α, 0),
// α = ½√((5 + √5)/2), is that times cos(θ/2) = √((5 + √5)/10), θ the angle of an edge: the
// rate per unit length along the flat edge, not along the arc.
TEST(AmbientDiceBezier, EdgeTangentsHaveThePapersBarycentricsUpToCosHalfEdge) {
  const double root5 = std::sqrt(5.0);
  const double alpha = 0.5 * std::sqrt((5.0 + root5) / 2.0), beta = -0.5 * std::sqrt((5.0 + root5) / 10.0);
  const double cosHalfEdge = std::sqrt((5.0 + root5) / 10.0);
  EXPECT_NEAR(cosHalfEdge, std::cos(0.5 * std::acos(1.0 / root5)), 1e-15);
  for (int t = 0; t < 20; ++t)
    for (int k = 0; k < 3; ++k)
      for (int m = 0; m < 3; ++m) {
        if (m == k) continue;
        const Eigen::Vector3d& v = ico().vertex(ico().triangle(t)[k]);
        const Eigen::Vector3d& w = ico().vertex(ico().triangle(t)[m]);
        const Eigen::Vector3d e = (w - v.dot(w) * v).normalized();
        Eigen::Vector3d expected = Eigen::Vector3d::Zero();
        expected[k] = -0.5;
        expected[m] = 0.5 * root5;
        const Eigen::Vector3d b = ico().inTriangle(t, e).spherical;
        EXPECT_LT((b - expected).norm(), 1e-14) << "triangle " << t;
        EXPECT_NEAR(b[k] * cosHalfEdge, beta, 1e-15);
        EXPECT_NEAR(b[m] * cosHalfEdge, alpha, 1e-15);
      }
}

TEST(AmbientDice, PiecewiseFunctionsAreContinuousAcrossEveryEdge) {
  const AmbientDiceBezierFunctions spherical(Barycentrics::Spherical), flat(Barycentrics::Flat);
  const AmbientDiceLinearFunctions linearFlat(Barycentrics::Flat), linearSpherical(Barycentrics::Spherical);
  const double epsilon = 1e-9;  // far below 1e-6 / |gradient| for these data
  std::mt19937_64 rng(5);
  for (const SphericalFunctions* f :
       std::vector<const SphericalFunctions*>{&spherical, &flat, &linearFlat, &linearSpherical}) {
    double worst = 0.0;
    for (int trial = 0; trial < 3; ++trial) {
      const Eigen::VectorXd data = randomData(f->count(), rng);
      for (const Edge& e : edges())
        for (double fraction : {0.05, 0.25, 0.5, 0.75, 0.95}) {
          const Eigen::Vector3d p = e.at(fraction);
          const Eigen::Vector3d left = (p + epsilon * e.normal).normalized(), right = (p - epsilon * e.normal).normalized();
          ASSERT_NE(ico().locate(left).triangle, ico().locate(right).triangle);
          worst = std::max(worst, std::abs(combination(*f, data, left) - combination(*f, data, right)));
        }
    }
    EXPECT_LT(worst, 1e-6) << "function set with " << f->count() << " functions";
  }
}

// The cross-edge derivative from either side at points inside every edge, relative to its size.
// With h = 1e-5 the one-sided differences are good to ~2e-8 (measured: the mismatch of the
// spherical patch falls as h², 2e-4, 2e-6, 2e-8 for h = 1e-3, 1e-4, 1e-5, until rounding at ~4e-9).
double worstCrossDerivativeMismatch(const AmbientDiceBezierFunctions& f, std::mt19937_64& rng) {
  const double h = 1e-5;
  double worst = 0.0;
  for (int trial = 0; trial < 3; ++trial) {
    const Eigen::VectorXd data = randomData(f.count(), rng);
    for (const Edge& e : edges())
      for (double fraction : {0.1, 0.3, 0.5, 0.7, 0.9}) {
        const Eigen::Vector3d p = e.at(fraction);
        const double left = derivativeAlong(f, data, p, e.normal, h);
        const double right = -derivativeAlong(f, data, p, -e.normal, h);
        worst = std::max(worst, std::abs(left - right) / (1.0 + std::max(std::abs(left), std::abs(right))));
      }
  }
  return worst;
}

// Measured: 2e-8 for the spherical patch (finite-difference error), 0.57 for the flat one.
TEST(AmbientDiceBezier, SphericalPatchIsC1AcrossEdgesAndFlatIsNot) {
  std::mt19937_64 rng(6);
  EXPECT_LT(worstCrossDerivativeMismatch(AmbientDiceBezierFunctions(Barycentrics::Spherical), rng), 1e-6);
  EXPECT_GT(worstCrossDerivativeMismatch(AmbientDiceBezierFunctions(Barycentrics::Flat), rng), 0.1);
}

// Values are interpolated exactly. Derivatives are in the paper's units (see the test above and
// AmbientDiceBezier.h): the patch's gradient on the sphere is the stored one over cos(θ/2), for
// both variants. One-sided differences with h = 1e-5 are good to ~1e-8 here.
TEST(AmbientDiceBezier, InterpolatesValuesAndScaledTangentDerivativesAtVertices) {
  const double h = 1e-5;
  const double gradientScale = std::sqrt(10.0 / (5.0 + std::sqrt(5.0)));  // 1/cos(θ/2) = 1.17557
  std::mt19937_64 rng(7);
  for (Barycentrics kind : {Barycentrics::Spherical, Barycentrics::Flat}) {
    SCOPED_TRACE(kind == Barycentrics::Spherical ? "spherical" : "flat");
    const AmbientDiceBezierFunctions f(kind);
    double worst = 0.0;
    for (int trial = 0; trial < 3; ++trial) {
      const Eigen::VectorXd data = randomData(f.count(), rng);
      for (int i = 0; i < 12; ++i) {
        const Eigen::Vector3d& v = ico().vertex(i);
        EXPECT_NEAR(combination(f, data, v), data[3 * i], 1e-12) << "vertex " << i;
        // Both ways along each axis, so each derivative is checked from two triangles.
        for (double sign : {1.0, -1.0}) {
          const double alongT = derivativeAlong(f, data, v, sign * ico().tangent(i), h);
          const double alongB = derivativeAlong(f, data, v, sign * ico().bitangent(i), h);
          worst = std::max(worst, std::abs(alongT - sign * gradientScale * data[3 * i + 1]));
          worst = std::max(worst, std::abs(alongB - sign * gradientScale * data[3 * i + 2]));
        }
      }
    }
    EXPECT_LT(worst, 1e-6);
  }
}

TEST(AmbientDice, LinearInterpolantsTakeTheVertexValues) {
  std::mt19937_64 rng(8);
  for (Barycentrics kind : {Barycentrics::Spherical, Barycentrics::Flat}) {
    const AmbientDiceLinearFunctions f(kind);
    const Eigen::VectorXd data = randomData(12, rng);
    for (int i = 0; i < 12; ++i) EXPECT_NEAR(combination(f, data, ico().vertex(i)), data[i], 1e-14);
  }
}

}  // namespace
}  // namespace baker
