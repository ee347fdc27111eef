#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "basis/BasisRegistry.h"
#include "basis/GramOperators.h"

namespace baker {
namespace {

// One unit in the last printed digit of a number as printed, e.g. "3.543e-3" → 1e-6.
double lastDigitUnit(const std::string& printed) {
  const std::size_t e = printed.find_first_of("eE");
  const std::string mantissa = printed.substr(0, e);
  const int exponent = e == std::string::npos ? 0 : std::stoi(printed.substr(e + 1));
  const std::size_t point = mantissa.find('.');
  const int decimals = point == std::string::npos ? 0 : int(mantissa.size() - point - 1);
  return std::pow(10.0, exponent - decimals);
}

struct PaperRow {
  const char* basis;
  bool runningSum;  // the paper's Ambient Dice rows use the running sum; its ambient cube row does not
  const char* printed[4];  // columns SH2…SH5 = orders L = 1…4
  // Tolerance in units of the last printed digit; 1 unless the paper's entry is off its own
  // row. Our values do not move in the 7th digit between quadrature orders 8, 16 and 32.
  double unitsAllowed[4] = {1, 1, 1, 1};
};

// Iwanicki & Sloan 2017, section 3.1.1: ‖I − B_shᵀ G⁻¹ B_sh‖_F.
const PaperRow kPaperTable[] = {
    {"ambient-cube", false, {"0.10825", "1.73543", "3.16228", "4.3589"}},
    // L=2: exact 0.184447; the paper's 0.18454 is 9 units off, yet its L=3 entry, which
    // contains the same band-2 error, reproduces to every digit (2.017509): the paper's
    // quadrature, not the reading, differs here.
    {"ad-linear", true, {"3.543e-3", "0.18454", "2.01751", "4.13203"}, {1, 10, 1, 1}},
    {"ad-srbf", true, {"3.971e-4", "1.427e-2", "2.0001", "4.12316"}},
    {"ad-cos2", true, {"2.229e-3", "3.153e-3", "2.0001", "4.12316"}},
    {"ad-rgb-flat", true, {"2.806e-4", "3.103e-3", "2.804e-2", "0.19754"}},
    // L=1: exact 3.8585e-4, printed 3.857e-4 (1.5 units); L=2…4 reproduce.
    {"ad-rgb", true, {"3.857e-4", "1.539e-3", "2.777e-2", "0.17101"}, {2, 1, 1, 1}},
};

// Every entry to within one unit of its last printed digit, but the two documented above.
TEST(FrobeniusTable, ReproducesThePapersShReproductionNorms) {
  for (const PaperRow& row : kPaperTable) {
    const auto basis = makeBasis(row.basis);
    const GramOperators ops(basis->functions(0), row.basis);
    const ShReproduction r = ops.shReproduction(4);
    for (int l = 1; l <= 4; ++l) {
      const double expected = std::stod(row.printed[l - 1]);
      const double computed = row.runningSum ? r.runningSum[l] : r.cumulative[l];
      EXPECT_NEAR(computed, expected, row.unitsAllowed[l - 1] * lastDigitUnit(row.printed[l - 1]))
          << row.basis << " L=" << l << " printed " << row.printed[l - 1] << " computed " << computed;
    }
  }
}

// The ambient cube's band-1 functions each have I − P diagonal 1/16, so cum(1) = √3/16.
TEST(FrobeniusTable, AmbientCubeBand1ClosedForm) {
  const auto basis = makeBasis("ambient-cube");
  const GramOperators ops(basis->functions(0), "ambient-cube");
  EXPECT_NEAR(ops.shReproduction(1).cumulative[1], std::sqrt(3.0) / 16.0, 1e-12);
}

// The notes: spherical Bézier does not reproduce constants (band-0 error 2.7e-4), flat does.
TEST(FrobeniusTable, ConstantReproductionOfTheBezierVariants) {
  const auto sphericalBasis = makeBasis("ad-rgb"), flatBasis = makeBasis("ad-rgb-flat");
  const GramOperators spherical(sphericalBasis->functions(0), "ad-rgb");
  const GramOperators flat(flatBasis->functions(0), "ad-rgb-flat");
  EXPECT_NEAR(spherical.shReproduction(0).cumulative[0], 2.7e-4, 0.05e-4);
  EXPECT_LT(flat.shReproduction(0).cumulative[0], 1e-10);
}

}  // namespace
}  // namespace baker
