#include "common/UpperBound.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

namespace baker {
namespace {

// The same index as std::upper_bound for every length from 0 to 40, on tables with runs of equal
// values (a CDF's empty bins), at every value of the table, between them, and outside it.
TEST(UpperBound, IsStdUpperBound) {
  std::mt19937 rng(5);
  std::uniform_int_distribution<int> step(0, 2);
  for (std::size_t count = 0; count <= 40; ++count) {
    std::vector<double> values;
    double running = 0.0;
    for (std::size_t i = 0; i < count; ++i) values.push_back(running += 0.25 * step(rng));
    std::vector<double> probes = {-1.0, 0.0, running + 1.0, 1e300, -0.0};
    for (double v : values)
      for (double near : {v, std::nextafter(v, -1e9), std::nextafter(v, 1e9), v + 0.125}) probes.push_back(near);
    for (double x : probes) {
      const auto expected = std::size_t(std::upper_bound(values.begin(), values.end(), x) - values.begin());
      EXPECT_EQ(upperBound(values.data(), values.size(), x), expected) << count << " values, x = " << x;
    }
    // No value is found not above NaN (std::upper_bound, testing !(x < v), would give count).
    EXPECT_EQ(upperBound(values.data(), values.size(), std::nan("")), 0u) << count << " values";
  }
}

}  // namespace
}  // namespace baker
