#include "basis/Quadrature.h"

#include <cmath>
#include <stdexcept>

namespace baker {

void gaussLegendre(int n, std::vector<double>* nodes, std::vector<double>* weights) {
  if (n <= 0) throw std::invalid_argument("Gauss-Legendre needs at least one node");
  nodes->assign(n, 0.0);
  weights->assign(n, 0.0);
  for (int i = 0; i < (n + 1) / 2; ++i) {
    // Newton's method on P_n from the Chebyshev-like first guess converges in a few steps.
    double x = std::cos(M_PI * (i + 0.75) / (n + 0.5));
    double derivative = 0.0;
    for (int iteration = 0; iteration < 100; ++iteration) {
      double p0 = 1.0, p1 = x;
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      if (n == 1) p0 = 1.0, p1 = x;
      derivative = n * (x * p1 - p0) / (x * x - 1.0);
      const double step = p1 / derivative;
      x -= step;
      if (std::abs(step) < 1e-16) break;
    }
    const double w = 2.0 / ((1.0 - x * x) * derivative * derivative);
    (*nodes)[i] = -x;
    (*nodes)[n - 1 - i] = x;
    (*weights)[i] = w;
    (*weights)[n - 1 - i] = w;
  }
}

DirectionSet gaussProductSphere(int zCount, int phiCount) {
  std::vector<double> z, wz;
  gaussLegendre(zCount, &z, &wz);
  DirectionSet set;
  for (int i = 0; i < zCount; ++i) {
    const double r = std::sqrt(std::max(0.0, 1.0 - z[i] * z[i]));
    for (int j = 0; j < phiCount; ++j) {
      const double phi = 2.0 * M_PI * (j + 0.5) / phiCount;
      set.directions.emplace_back(r * std::cos(phi), r * std::sin(phi), z[i]);
      set.weights.push_back(wz[i] * 2.0 * M_PI / phiCount);
    }
  }
  return set;
}

}  // namespace baker
