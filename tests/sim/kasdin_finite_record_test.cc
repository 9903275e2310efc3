// The O(log N) finite-record flicker expectation (sim/kasdin_finite_record.h) against the direct
// O(N) sum of docs/theory.md §2.5.3 (FiniteRecordAvar on the Kasdin running sums), an independent slow
// computation: every piece (exact head, Gregory ends, Gauss-Legendre panels) must reproduce it.
#include <cmath>
#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include "sim/avar_theory.h"
#include "sim/flicker_noise.h"
#include "sim/kasdin_finite_record.h"

namespace allanlab::sim {
namespace {

TEST(KasdinFiniteRecord, CumulativeMatchesRecursion) {
  const std::vector<double> s = CumulativeSum(KasdinCoefficients(20001));
  for (std::int64_t v : {0, 1, 2, 10, 127, 128, 129, 130, 1000, 20000}) {
    EXPECT_NEAR(KasdinCumulative(static_cast<double>(v)), s[static_cast<std::size_t>(v)],
                2e-15 * s[static_cast<std::size_t>(v)])
        << "v=" << v;
  }
  // Continuous between the integers: S(v) = 2 Gamma(v + 3/2) / (sqrt(pi) Gamma(v + 1)).
  for (double v : {0.5, 3.25, 127.5, 128.5, 5000.5}) {
    const double ref = static_cast<double>(
        2.0L / std::sqrt(3.14159265358979323846264338327950288L) *
        std::exp(std::lgamma(static_cast<long double>(v) + 1.5L) - std::lgamma(static_cast<long double>(v) + 1.0L)));
    EXPECT_NEAR(KasdinCumulative(v), ref, 1e-12 * ref) << "v=" << v;
  }
  EXPECT_EQ(KasdinCumulative(-1.0), 0.0);
}

TEST(KasdinFiniteRecord, MatchesDirectSum) {
  for (std::int64_t n : {std::int64_t{300}, std::int64_t{4096}, std::int64_t{100003},
                         std::int64_t{1} << 20}) {
    const std::vector<double> s = CumulativeSum(KasdinCoefficients(n));
    const RecordShape shape{n, AvarEstimatorKind::kOverlapping};
    for (std::int64_t m : {std::int64_t{1}, std::int64_t{2}, std::int64_t{7}, std::int64_t{127},
                           std::int64_t{128}, std::int64_t{129}, std::int64_t{150}, std::int64_t{300},
                           n / 16, n / 4 - 1, n / 3, n / 2}) {
      if (m < 1 || 2 * m > n) continue;
      const double direct = FiniteRecordAvar(s, 1.0, m, 0, shape);
      const double fast = KasdinOverlappingAvar(m, n);
      EXPECT_NEAR(fast, direct, 1e-12 * direct) << "n=" << n << " m=" << m;
    }
  }
}

// FlickerNoise::ExpectedAvar takes the fast path for overlapping records; the non-overlapping
// one keeps the direct sum.
TEST(KasdinFiniteRecord, FlickerNoiseUsesIt) {
  const FlickerNoise f{2.0};
  const RecordShape shape{50000, AvarEstimatorKind::kOverlapping};
  EXPECT_NEAR(f.ExpectedAvar(999, 1.0, shape), 4.0 * KasdinOverlappingAvar(999, 50000), 1e-15);
}

// The memo gives back the bits of a fresh computation, on the first call and on later ones.
TEST(KasdinFiniteRecord, MemoisedValuesAreTheFreshBits) {
  for (std::int64_t n : {4099, 777777}) {
    for (std::int64_t m : {std::int64_t{1}, std::int64_t{2}, std::int64_t{3}, std::int64_t{129}, std::int64_t{1001}, n / 3, n / 2}) {
      const double fresh = KasdinOverlappingAvarUncached(m, n);
      EXPECT_EQ(KasdinOverlappingAvar(m, n), fresh) << "m " << m << " n " << n;
      EXPECT_EQ(KasdinOverlappingAvar(m, n), fresh) << "m " << m << " n " << n;
    }
  }
  EXPECT_EQ(KasdinOverlappingAvar(0, 100), 0.0);
  EXPECT_EQ(KasdinOverlappingAvar(51, 100), 0.0);
}

}  // namespace
}  // namespace allanlab::sim
