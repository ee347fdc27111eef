// basis/LegendreResponse.h against closed forms derived by hand and against a direct double
// integral of the lobe times the clamped cosine.
#include <gtest/gtest.h>

#include <cmath>

#include "basis/LegendreResponse.h"
#include "common/Error.h"

namespace baker {
namespace {

// K(n) = ∫ g(a·ω) max(0, n·ω) dω by the midpoint rule in the lobe's frame, n at angle β to a.
double directResponse(const std::function<double(double)>& g, double beta) {
  constexpr int kTheta = 1200, kPhi = 2400;
  double sum = 0.0;
  for (int i = 0; i < kTheta; ++i) {
    const double theta = M_PI * (i + 0.5) / kTheta, cosTheta = std::cos(theta), sinTheta = std::sin(theta);
    const double lobe = g(cosTheta) * sinTheta;
    for (int j = 0; j < kPhi; ++j) {
      const double phi = 2.0 * M_PI * (j + 0.5) / kPhi;
      const double cosine = std::sin(beta) * sinTheta * std::cos(phi) + std::cos(beta) * cosTheta;
      if (cosine > 0.0) sum += lobe * cosine;
    }
  }
  return sum * (M_PI / kTheta) * (2.0 * M_PI / kPhi);
}

TEST(LegendreResponse, ClampedPowersHaveTheirClosedForms) {
  const LegendreResponse square([](double t) { return t > 0.0 ? t * t : 0.0; }, "square");
  const LegendreResponse fourth([](double t) { return t > 0.0 ? t * t * t * t : 0.0; }, "fourth");
  // A_l = 0 for odd l > 1 and the lobes have no even band above their degree: finite series.
  EXPECT_EQ(square.coefficients().size(), 3u);
  EXPECT_EQ(fourth.coefficients().size(), 5u);
  for (double x = -1.0; x <= 1.0; x += 0.125) {
    EXPECT_NEAR(square(x), M_PI * (1.0 + x) * (1.0 + x) / 8.0, 1e-12) << x;
    EXPECT_NEAR(fourth(x), M_PI * (1.0 / 16 + x / 6 + x * x / 8 - x * x * x * x / 48), 1e-12) << x;
  }
}

TEST(LegendreResponse, SphericalGaussiansMatchADirectIntegral) {
  for (double lambda : {0.5, 8.0, 60.0}) {
    const auto g = [lambda](double t) { return std::exp(lambda * (t - 1.0)); };
    const LegendreResponse response(g, "sg");
    const double peak = response(1.0);
    for (double beta : {0.0, 0.4, 1.2, M_PI / 2, 2.0, 2.9, M_PI}) {
      EXPECT_NEAR(response(std::cos(beta)), directResponse(g, beta), 2e-5 * peak) << "lambda " << lambda << " beta " << beta;
    }
  }
}

TEST(LegendreResponse, ALobeTooSharpIsRefused) {
  EXPECT_THROW(LegendreResponse([](double t) { return std::exp(1e6 * (t - 1.0)); }, "sg-12"), NumericalError);
}

}  // namespace
}  // namespace baker
