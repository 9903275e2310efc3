#pragma once
// Allan curves as the fit tests build them: averaging factors spaced evenly in log m, and an
// AvarCurve from given values (exact expectations or one simulated record's estimates).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "estimators/avar.h"
#include "estimators/fit/avar_curve.h"

namespace allanlab::testing_support {

// Distinct averaging factors 1 ... <= max_m, `per_decade` per decade (rounded, ascending).
inline std::vector<std::int64_t> LogDense(std::int64_t max_m, double per_decade) {
  std::vector<std::int64_t> ms;
  for (double x = 1; x <= static_cast<double>(max_m); x *= std::pow(10.0, 1.0 / per_decade)) {
    const auto m = static_cast<std::int64_t>(std::llround(x));
    if (ms.empty() || m > ms.back()) ms.push_back(m);
  }
  return ms;
}

// The curve of a record of n samples at `rate_hz` with values `avar` [(rad/s)^2] at `ms`.
inline estimators::AvarCurve Curve(double rate_hz, std::int64_t n,
                                   const std::vector<std::int64_t>& ms,
                                   const std::vector<double>& avar) {
  estimators::AvarCurve c;
  c.sample_clock = SampleClock::FromPeriodS(1.0 / rate_hz);
  c.num_samples = n;
  c.m = ms;
  for (std::int64_t m : ms) c.tau_s.push_back(static_cast<double>(m) * c.sample_clock.period_s());
  c.avar = avar;
  return c;
}

// The overlapping curve `allanlab fit` takes of a rate record: dense:10 taus, Greenhall-Riley
// EDFs, taus with a positive value.
inline estimators::AvarCurve DenseCurveOf(const std::vector<double>& rate, double rate_hz) {
  estimators::AvarOptions o;
  o.statistic = estimators::Statistic::kAllanOverlapping;
  std::string why;
  EXPECT_TRUE(estimators::TauGridOptions::Parse("dense:10", &o.taus, &why)) << why;
  o.sample_clock = SampleClock::FromPeriodS(1.0 / rate_hz);
  estimators::AvarSummary s;
  EXPECT_TRUE(estimators::ComputeAvar(o, rate, &s)) << s.message;
  estimators::AvarCurve c;
  c.sample_clock = o.sample_clock;
  c.num_samples = s.num_samples;
  c.estimator = sim::AvarEstimatorKind::kOverlapping;
  for (const estimators::AvarPoint& p : s.points) {
    if (!(p.value > 0.0)) continue;
    c.m.push_back(p.m);
    c.tau_s.push_back(p.tau_s);
    c.avar.push_back(p.value);
    c.edf.push_back(p.edf > 0.0 ? p.edf : 1.0);
  }
  return c;
}

}  // namespace allanlab::testing_support
