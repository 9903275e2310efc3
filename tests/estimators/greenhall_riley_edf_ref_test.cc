// Tier a: the Greenhall & Riley (2003) EDF algorithm reproduces the reference
// values of docs/theory.md §3.4 (allantools' edf_greenhall, the algorithm Stable32
// uses; four decimals, checked to 1e-4 relative) and the "GR" columns of the
// §2.2 table (three decimals). For white phase the algorithm is exact, which
// checks the case-4 branch against the exact recipe of §2.1.
#include <cmath>
#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include "estimators/confidence.h"
#include "estimators/exact_avar_variance.h"

namespace allanlab::estimators {
namespace {

struct Case {
  int alpha, d;
  std::int64_t m, n_phase;
  bool overlapping, modified;
  double edf;
};

::testing::AssertionResult EdfNear(const Case &c, double tolerance) {
  const double edf = GreenhallRileyEdf(c.alpha, c.d, c.m, c.n_phase,
                                       c.overlapping, c.modified);
  if (std::abs(edf - c.edf) <= tolerance)
    return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure()
         << "alpha=" << c.alpha << " d=" << c.d << " m=" << c.m
         << " N=" << c.n_phase
         << (c.overlapping ? " overlapping" : " non-overlapping")
         << (c.modified ? " modified" : "") << ": expected " << c.edf
         << ", got " << edf << ", tolerance " << tolerance;
}

TEST(GreenhallRileyEdf, UnitValuesOfTheory) {
  const std::vector<Case> cases = {
      // Allan, white FM, PHASE.DAT length: small-m sums and (m = 128) the Table
      // 2 branch.
      {0, 2, 1, 1001, true, false, 782.0303},
      {0, 2, 2, 1001, true, false, 540.6812},
      {0, 2, 8, 1001, true, false, 165.9878},
      {0, 2, 128, 1001, true, false, 9.5510},
      {0, 2, 128, 1001, false, false, 4.2353},
      // Each noise type, overlapping Allan.
      {-1, 2, 10, 1000, true, false, 114.5523},
      {-2, 2, 10, 1000, true, false, 90.9460},
      {2, 2, 10, 1000, true, false, 506.6589},
      {1, 2, 10, 1000, true, false, 247.0561},
      // Modified Allan (F = 1).
      {0, 2, 10, 1000, true, true, 94.5375},
      {-1, 2, 10, 1000, true, true, 93.1775},
      // Hadamard (d = 3).
      {0, 3, 10, 1000, true, false, 113.5826},
      {-2, 3, 10, 1000, true, false, 94.2273},
      // Large-r table branches (J > J_max).
      {-1, 2, 100, 10000, true, false, 115.5424},
      {-2, 2, 1000, 10000, true, false, 7.7444},
      {0, 2, 1000, 100000, true, false, 147.7538},
  };
  for (const Case &c : cases)
    EXPECT_TRUE(EdfNear(c, 1e-4 * c.edf));
}

// docs/theory.md §3.2, "ovl GR" and "non-ovl GR" columns; N there counts rate
// samples, the algorithm takes phase points N + 1.
TEST(GreenhallRileyEdf, TheoryTableColumns) {
  struct Row {
    int alpha;
    std::int64_t n_rate, m;
    double overlapping, non_overlapping;
  };
  const std::vector<Row> rows = {
      {0, 100, 1, 77.683, 77.683},    {0, 100, 10, 11.824, 6.298},
      {0, 1000, 10, 135.071, 66.988}, {0, 1000, 100, 12.815, 6.231},
      {0, 1000, 300, 3.157, 1.600},   {-2, 1000, 10, 91.038, 87.958},
      {-2, 1000, 100, 7.754, 8.100},  {-1, 1000, 10, 114.669, 87.778},
      {-1, 1000, 100, 9.948, 8.092},  {2, 1000, 10, 507.173, 51.180},
      {2, 1000, 100, 440.207, 4.909},
  };
  for (const Row &r : rows) {
    EXPECT_TRUE(EdfNear(
        {r.alpha, 2, r.m, r.n_rate + 1, true, false, r.overlapping}, 5e-4));
    EXPECT_TRUE(EdfNear(
        {r.alpha, 2, r.m, r.n_rate + 1, false, false, r.non_overlapping},
        5e-4));
  }
  EXPECT_TRUE(EdfNear({-2, 2, 1, 1001, true, false, 762.3},
                      0.05)); // printed to one decimal
}

// White phase (rate = first difference of white angle) has R = (2, -1, 0, ...).
// Greenhall & Riley's case 4 is exact for it, including r <= d, where few terms
// remain and allantools stops.
TEST(GreenhallRileyEdf, WhitePhaseEqualsExactRecipe) {
  const std::int64_t n_rate = 1000;
  std::vector<double> r(n_rate + 2 * 500, 0.0);
  r[0] = 2.0;
  r[1] = -1.0;
  for (std::int64_t m : {1, 3, 10, 100, 250, 300, 333, 400, 499, 500}) {
    for (bool overlapping : {true, false}) {
      const sim::RecordShape shape{
          n_rate, overlapping ? sim::AvarEstimatorKind::kOverlapping
                              : sim::AvarEstimatorKind::kNonOverlapping};
      const double exact = ExactAvarMoments(r, m, shape).edf();
      EXPECT_NEAR(GreenhallRileyEdf(2, 2, m, n_rate + 1, overlapping, false),
                  exact, 1e-9 * exact)
          << "m=" << m << (overlapping ? " overlapping" : " non-overlapping");
    }
  }
}

// Where J crosses J_max = 100 the algorithm switches from the exact sum to the
// Table 1/2/3 expansions. EDF ~ 1/m there, so EDF(m) m must not jump across the
// switch: the sums keep the O(1/m) effect of the tau0 averaging that the tables
// drop (3-4 % for white FM at m ~ 30), while a wrong table entry would show as
// a step of tens of percent. Unmodified white phase (case 4) has no switch.
TEST(GreenhallRileyEdf, TableBranchesJoinTheExactSums) {
  for (int d : {2, 3}) {
    const std::int64_t below = 100 / (d + 1); // J = (d + 1) m <= 100
    const std::int64_t above = below + 1;
    for (int alpha = 2; alpha + 2 * d > 1 && alpha >= -4; --alpha) {
      for (bool modified : {false, true}) {
        if (alpha == 2 && !modified)
          continue;
        const double e_below =
            GreenhallRileyEdf(alpha, d, below, 100000, true, modified) * below;
        const double e_above =
            GreenhallRileyEdf(alpha, d, above, 100000, true, modified) * above;
        EXPECT_NEAR(e_above / e_below, 1.0, 0.05)
            << "alpha=" << alpha << " d=" << d << (modified ? " modified" : "");
      }
    }
  }
}

TEST(GreenhallRileyEdf, OutsideTheDomainIsZero) {
  EXPECT_EQ(GreenhallRileyEdf(-1, 1, 4, 1000, true, false),
            0.0); // alpha + 2d = 1
  EXPECT_EQ(GreenhallRileyEdf(-3, 2, 4, 1000, true, false), 0.0);
  EXPECT_EQ(GreenhallRileyEdf(0, 4, 4, 1000, true, false), 0.0);
  EXPECT_EQ(GreenhallRileyEdf(0, 2, 0, 1000, true, false), 0.0);
  EXPECT_EQ(GreenhallRileyEdf(0, 2, 500, 1000, true, false),
            0.0); // L = 2m + 1 > N
  EXPECT_GT(GreenhallRileyEdf(0, 2, 500, 1001, true, false), 0.0); // one term
}

} // namespace
} // namespace allanlab::estimators
