// Ar1Avar (closed form where m(1 - phi) >= 0.01, lag sum below) against the definition: the
// variance of adjacent block means from the AR(1) autocovariance, summed directly.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

#include "sim/avar_theory.h"
#include "sim/gauss_markov.h"

namespace allanlab::sim {
namespace {

// AVAR(m) = Var(block mean) - Cov(adjacent block means), autocovariance phi^|k|.
double Direct(std::int64_t m, double phi) {
  long double var = 0.0L, cov = 0.0L;
  for (std::int64_t i = 0; i < m; ++i) {
    for (std::int64_t j = 0; j < m; ++j) {
      var += std::pow(static_cast<long double>(phi), std::abs(i - j));
      cov += std::pow(static_cast<long double>(phi), m + j - i);
    }
  }
  return static_cast<double>((var - cov) / (static_cast<long double>(m) * m));
}

TEST(Ar1AvarTest, MatchesTheDefinitionAcrossTheClosedFormThreshold) {
  for (std::int64_t m : {1, 2, 5, 40, 300}) {
    for (double q : {1e-6, 1e-4, 3e-3, 0.05, 0.5, 0.9}) {
      const double expected = Direct(m, 1.0 - q);
      EXPECT_NEAR(Ar1Avar(m, 1.0 - q, 2.5) / (2.5 * expected), 1.0, 1e-9) << "m " << m << " q " << q;
    }
  }
}

// The lag sum the small-m(1 - phi) series replaced, in long double.
double LagSum(std::int64_t m, double phi) {
  const double log_phi = std::log(phi);
  long double sum = 0.0L;
  for (std::int64_t j = 1; j < 2 * m; ++j) sum += 2.0L * AllanLagWeight(m, j) * std::expm1(static_cast<double>(j) * log_phi);
  return static_cast<double>(sum / (2.0L * m * m));
}

// Below the closed form's threshold (m q < 0.01) the series is the lag sum to round-off, from
// m = 1 to half a 1e6-sample record and up to the threshold.
TEST(Ar1AvarTest, SeriesIsTheLagSumBelowTheThreshold) {
  for (std::int64_t m : {1, 2, 3, 7, 64, 1000, 31623, 500000}) {
    for (double mq : {1e-9, 1e-7, 1e-4, 3e-3, 0.0099}) {
      const double q = mq / static_cast<double>(m);  // phi = 1 - q stays below 1 in double
      const double expected = LagSum(m, 1.0 - q);
      EXPECT_NEAR(Ar1Avar(m, 1.0 - q, 1.0) / expected, 1.0, 1e-12) << "m " << m << " m q " << mq;
    }
  }
}

// The series as it was before its moments were kept per m (sim/gauss_markov.cc): the kept
// moments must give the same bits, on first use and on reuse.
long double PowerSumReference(int p, long double n) {
  static constexpr long double kBernoulli[12] = {1.0L, 0.5L, 1.0L / 6, 0.0L, -1.0L / 30, 0.0L,
                                                 1.0L / 42, 0.0L, -1.0L / 30, 0.0L, 5.0L / 66, 0.0L};
  long double sum = 0.0L, binomial = 1.0L;
  for (int k = 0; k <= p; ++k) {
    if (kBernoulli[k] != 0.0L) {
      long double power = 1.0L;
      for (int e = 0; e < p + 1 - k; ++e) power *= n;
      sum += binomial * kBernoulli[k] * power;
    }
    binomial = binomial * static_cast<long double>(p + 1 - k) / static_cast<long double>(k + 1);
  }
  return sum / static_cast<long double>(p + 1);
}

double SeriesReference(std::int64_t m, double phi, double variance) {
  const long double x = -static_cast<long double>(std::log(phi));
  const long double ml = static_cast<long double>(m);
  long double sum = 0.0L, power = 1.0L;
  for (int p = 1; p <= 9; ++p) {
    power *= -x / static_cast<long double>(p);
    const long double upper_p = PowerSumReference(p, 2.0L * ml - 1.0L) - PowerSumReference(p, ml);
    const long double upper_p1 = PowerSumReference(p + 1, 2.0L * ml - 1.0L) - PowerSumReference(p + 1, ml);
    const long double moment =
        2.0L * ml * PowerSumReference(p, ml) - 3.0L * PowerSumReference(p + 1, ml) + upper_p1 - 2.0L * ml * upper_p;
    sum += power * moment;
  }
  return static_cast<double>(variance * sum / (ml * ml));
}

TEST(Ar1AvarTest, KeptSeriesMomentsGiveTheSameBits) {
  for (int pass = 0; pass < 2; ++pass) {
    for (std::int64_t m : {1, 2, 3, 7, 64, 1000, 31623}) {
      for (double mq : {1e-9, 1e-4, 0.0099}) {
        const double phi = 1.0 - mq / static_cast<double>(m);
        EXPECT_EQ(Ar1Avar(m, phi, 2.5), SeriesReference(m, phi, 2.5)) << "m " << m << " m q " << mq;
      }
    }
  }
}

}  // namespace
}  // namespace allanlab::sim
