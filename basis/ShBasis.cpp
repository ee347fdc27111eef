#include "basis/ShBasis.h"

#include <array>
#include <vector>

#include "basis/BasisRegistry.h"

namespace baker {

// Global support: every coefficient is read, so the gain over the default is only in
// evaluating the harmonics once into a buffer on the stack for all three channels.
Eigen::Vector3f ShBasis::reconstruct(const float* coefficients, const Eigen::Vector3d& d) const {
  std::array<double, 81> values;  // order 8, the largest the registry makes
  std::vector<double> large;
  double* y = values.data();
  if (sh_.count() > int(values.size())) {
    large.resize(sh_.count());
    y = large.data();
  }
  sh_.evaluate(d, y);
  const int n = sh_.count();
  double r = 0.0, g = 0.0, b = 0.0;
  for (int i = 0; i < n; ++i) {
    r += y[i] * coefficients[i];
    g += y[i] * coefficients[n + i];
    b += y[i] * coefficients[2 * n + i];
  }
  return {float(r), float(g), float(b)};
}

namespace {

const BasisRegistration kShBases({10,
                                  {"sh-l0", "sh-l1", "sh-l2", "sh-l3", "sh-l4", "sh-l5", "sh-l6", "sh-l7", "sh-l8"},
                                  {},
                                  [](const std::string& name, const BasisParameters&) -> std::unique_ptr<Basis> {
                                    for (int l = 0; l <= 8; ++l)
                                      if (name == "sh-l" + std::to_string(l)) return std::make_unique<ShBasis>(l);
                                    return nullptr;
                                  }});

}  // namespace

}  // namespace baker
