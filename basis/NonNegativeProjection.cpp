#include "basis/NonNegativeProjection.h"

#include <Eigen/Cholesky>
#include <vector>

#include "basis/DirectionSet.h"

namespace baker {

Eigen::VectorXd nonNegativeProjection(const Eigen::MatrixXd& gram, const Eigen::VectorXd& moments) {
  const int n = int(moments.size());
  const double tolerance = 1e-12 * std::max(1.0, moments.cwiseAbs().maxCoeff());
  Eigen::VectorXd c = Eigen::VectorXd::Zero(n);
  std::vector<bool> active(n, false);  // "passive" set of Lawson–Hanson: coefficients free to move

  // Solves the unconstrained problem on the active coefficients, zero elsewhere.
  auto solveActive = [&]() {
    std::vector<int> index;
    for (int i = 0; i < n; ++i)
      if (active[i]) index.push_back(i);
    const int k = int(index.size());
    Eigen::MatrixXd g(k, k);
    Eigen::VectorXd m(k);
    for (int a = 0; a < k; ++a) {
      m[a] = moments[index[a]];
      for (int b = 0; b < k; ++b) g(a, b) = gram(index[a], index[b]);
    }
    const Eigen::VectorXd solution = g.ldlt().solve(m);
    Eigen::VectorXd s = Eigen::VectorXd::Zero(n);
    for (int a = 0; a < k; ++a) s[index[a]] = solution[a];
    return s;
  };

  // Each outer step frees one coefficient; inner steps only ever fix coefficients again, so
  // 3n outer steps is a generous bound that is never reached on well-posed problems.
  for (int outer = 0; outer < 3 * n; ++outer) {
    const Eigen::VectorXd gradient = moments - gram * c;  // descent direction of the objective
    int best = -1;
    for (int i = 0; i < n; ++i)
      if (!active[i] && gradient[i] > tolerance && (best < 0 || gradient[i] > gradient[best])) best = i;
    if (best < 0) break;  // Karush–Kuhn–Tucker conditions hold
    active[best] = true;
    for (int inner = 0; inner < n; ++inner) {
      const Eigen::VectorXd s = solveActive();
      double step = 1.0;
      for (int i = 0; i < n; ++i)
        if (active[i] && s[i] <= 0.0) step = std::min(step, c[i] / (c[i] - s[i]));
      if (step >= 1.0) {
        c = s;
        break;
      }
      c += step * (s - c);
      for (int i = 0; i < n; ++i)
        if (active[i] && c[i] <= tolerance) {
          active[i] = false;
          c[i] = 0.0;
        }
    }
  }
  return c;
}

bool functionsAreNonNegative(const SphericalFunctions& functions) {
  const DirectionSet directions = sphericalFibonacci(16384);
  std::vector<double> values(std::size_t(functions.count()));
  for (const Eigen::Vector3d& d : directions.directions) {
    functions.evaluate(d, values.data());
    for (double v : values)
      if (v < -1e-9) return false;
  }
  return true;
}

}  // namespace baker
