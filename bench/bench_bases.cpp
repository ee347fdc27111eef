// Per basis: nanoseconds per direction of the fast reconstruction (Basis::reconstruct) and of
// the dense default that evaluates every function, their ratio from the same run, and the time
// to build the Gram inverse and the radiance→irradiance operator.
//
//   build/bench/bench_bases [--json]
#include <fmt/format.h>

#include <chrono>
#include <iostream>
#include <nlohmann/json.hpp>
#include <random>

#include "basis/BasisRegistry.h"
#include "basis/GramOperators.h"
#include "cli/CommandLine.h"

using namespace baker;

namespace {

double seconds(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The dense path: what reconstruction costs without local support.
class DenseView : public Basis {
 public:
  explicit DenseView(const Basis& basis) : basis_(basis) {}
  std::string name() const override { return basis_.name(); }
  std::string family() const override { return basis_.family(); }
  ColorSpace colorSpace() const override { return basis_.colorSpace(); }
  const SphericalFunctions& functions(int c) const override { return basis_.functions(c); }
  int coefficientsPerLookup() const override { return basis_.totalCoefficients(); }

 private:
  const Basis& basis_;
};

// Best of several passes over a fixed set of directions, in ns per direction.
double nsPerDirection(const Basis& basis, const std::vector<float>& coefficients,
                      const std::vector<Eigen::Vector3d>& directions) {
  double best = 1e30;
  volatile float sink = 0.0f;
  for (int pass = 0; pass < 5; ++pass) {
    const auto start = std::chrono::steady_clock::now();
    Eigen::Vector3f sum = Eigen::Vector3f::Zero();
    for (const Eigen::Vector3d& d : directions) sum += basis.reconstruct(coefficients.data(), d);
    sink = sink + sum.sum();
    best = std::min(best, seconds(start) * 1e9 / directions.size());
  }
  return best;
}

}  // namespace

int main(int argc, char** argv) {
  bool json = false;
  CLI::App app{"Per basis: reconstruction cost (fast against dense) and the time to build its operators."};
  app.add_flag("--json", json, "print the results as JSON");
  return runGuarded("bench_bases", app, argc, argv, [&] {
    std::mt19937 rng(42);
    std::normal_distribution<double> normal;
    std::vector<Eigen::Vector3d> directions(200000);
    for (Eigen::Vector3d& d : directions) d = Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized();

    nlohmann::json rows = nlohmann::json::array();
    if (!json)
      std::cout << fmt::format("{:<14} {:>6} {:>5} {:>10} {:>10} {:>8} {:>10} {:>12}\n", "basis", "stored", "read",
                               "fast ns", "dense ns", "dense/fast", "gram ms", "irradiance ms");
    for (const std::string& name : basisNames()) {
      const auto basis = makeBasis(name);
      std::vector<float> coefficients(basis->totalCoefficients());
      for (float& c : coefficients) c = float(normal(rng));
      const double fast = nsPerDirection(*basis, coefficients, directions);
      const double dense = nsPerDirection(DenseView(*basis), coefficients, directions);
      auto start = std::chrono::steady_clock::now();
      const GramOperators ops(basis->functions(0), name);
      const double gramMs = seconds(start) * 1e3;
      start = std::chrono::steady_clock::now();
      int order = 0;
      ops.radianceToIrradiance({}, &order);
      const double irradianceMs = seconds(start) * 1e3;
      rows.push_back({{"basis", name},
                      {"coefficients_stored", basis->totalCoefficients()},
                      {"coefficients_per_lookup", basis->coefficientsPerLookup()},
                      {"reconstruct_ns_per_direction", fast},
                      {"dense_ns_per_direction", dense},
                      {"dense_over_fast", dense / fast},
                      {"gram_build_ms", gramMs},
                      {"irradiance_operator_build_ms", irradianceMs},
                      {"irradiance_operator_sh_order", order}});
      if (!json)
        std::cout << fmt::format("{:<14} {:>6} {:>5} {:>10.1f} {:>10.1f} {:>8.2f} {:>10.1f} {:>12.1f}\n", name,
                                 basis->totalCoefficients(), basis->coefficientsPerLookup(), fast, dense, dense / fast,
                                 gramMs, irradianceMs);
    }
    if (json) std::cout << nlohmann::json{{"bases", rows}}.dump(2) << "\n";
    return 0;
  });
}
