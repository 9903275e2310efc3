// The per-term cache of a fit's additive terms returns, summed in term order, exactly (bit for
// bit) the expected AVAR of the whole model it replaces, with and without a band-limit, on the
// first call and from the cache; and declines a term that is not additive.
#include "estimators/fit/additive_term_avar.h"

#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "estimators/fit/parametric_fit.h"
#include "tests/support/fit_curves.h"

namespace allanlab::estimators {
namespace {

AvarCurve Grid(std::int64_t n, double fs) {
  AvarCurve c;
  c.sample_clock = SampleClock::FromPeriodS(1.0 / fs);
  c.num_samples = n;
  c.m = testing_support::LogDense(n / 2, 10);
  for (std::int64_t m : c.m) {
    c.tau_s.push_back(static_cast<double>(m) / fs);
    c.avar.push_back(1.0);
  }
  return c;
}

void ExpectSameAsWholeModel(const sim::SensorModel& base, const std::vector<double>& band_key) {
  const AvarCurve curve = Grid(20000, 100.0);
  const std::vector<std::shared_ptr<const ParametricTerm>> terms = {
      MakeGaussMarkovTerm(), MakeHarmonicTerm(), MakeRandomTelegraphTerm()};
  const std::vector<std::vector<double>> params = {{3e-4, 2.5}, {1e-4, 0.7}, {2e-4, 9.0}};
  sim::SensorModel whole = base;
  for (std::size_t t = 0; t < terms.size(); ++t) terms[t]->ApplyTo(params[t], &whole);
  const std::vector<double> expected = ModelAvarOnCurve(whole, curve);
  AdditiveTermAvar cache(curve);
  for (int pass = 0; pass < 2; ++pass) {  // computed, then from the cache
    std::vector<double> sum(curve.size(), 0.0);
    for (std::size_t t = 0; t < terms.size(); ++t) {
      const std::vector<double>* part = cache.Part(t, *terms[t], params[t], base, band_key);
      ASSERT_NE(part, nullptr);
      for (std::size_t k = 0; k < sum.size(); ++k) sum[k] += (*part)[k];
    }
    for (std::size_t k = 0; k < sum.size(); ++k) EXPECT_EQ(sum[k], expected[k]) << "pass " << pass << " k " << k;
  }
}

TEST(AdditiveTermAvar, SumIsTheWholeModelsBits) {
  sim::SensorModel base;
  base.sample_clock = SampleClock::FromRateHz(100.0);
  ExpectSameAsWholeModel(base, {});
}

TEST(AdditiveTermAvar, SumIsTheWholeModelsBitsBehindABandLimit) {
  sim::SensorModel base;
  base.sample_clock = SampleClock::FromRateHz(100.0);
  const double cutoff_hz = 7.0;
  MakeBandLimitTerm(sim::LowPassKind::kFirstOrder)->ApplyTo(std::vector<double>{cutoff_hz}, &base);
  ASSERT_TRUE(base.band_limit.enabled());
  ExpectSameAsWholeModel(base, {cutoff_hz});
}

TEST(AdditiveTermAvar, DeclinesAModifier) {
  const AvarCurve curve = Grid(20000, 100.0);
  sim::SensorModel base;
  base.sample_clock = SampleClock::FromRateHz(100.0);
  AdditiveTermAvar cache(curve);
  const auto band = MakeBandLimitTerm(sim::LowPassKind::kFirstOrder);
  EXPECT_EQ(cache.Part(0, *band, std::vector<double>{7.0}, base, {}), nullptr);
}

}  // namespace
}  // namespace allanlab::estimators
