#pragma once
#include <cmath>
#include <vector>

namespace baker::test {

// The mean of estimates from independent seeds and its standard error (from their spread).
struct SeedStatistics {
  double mean = 0.0, standardError = 0.0;
};

inline SeedStatistics overSeeds(const std::vector<double>& values) {
  SeedStatistics s;
  for (double v : values) s.mean += v;
  s.mean /= double(values.size());
  double squares = 0.0;
  for (double v : values) squares += (v - s.mean) * (v - s.mean);
  s.standardError = std::sqrt(squares / double(values.size() - 1) / double(values.size()));
  return s;
}

}  // namespace baker::test
