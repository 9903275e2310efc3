// The shared GLS covariance models of a diagnosis (experiments/diagnosis/curve_covariances.h): one
// per curve shape, and a fit handed the shared model (built with every term) gives the same bits
// as the fit that builds its own from the terms it fits.
#include "experiments/diagnosis/curve_covariances.h"

#include <gtest/gtest.h>

#include "estimators/avar.h"
#include "estimators/fit/fit_avar_model.h"
#include "sim/sensor_model.h"
#include "sim/white_rate_noise.h"
#include "sim/random_walk_rate.h"

namespace allanlab::experiments::detail {
namespace {

using estimators::Coefficient;

estimators::AvarCurve CurveOf(std::int64_t n, std::uint64_t seed) {
  sim::SensorModel model;
  model.sample_clock = SampleClock::FromRateHz(100.0);
  model.terms = {sim::WhiteRateNoise{1e-4}, sim::RandomWalkRate{1e-5}};
  estimators::AvarOptions o;
  o.statistic = estimators::Statistic::kAllanOverlapping;
  o.sample_clock = model.sample_clock;
  o.taus.kind = estimators::TauGridKind::kLogDense;
  estimators::AvarSummary s;
  EXPECT_TRUE(estimators::ComputeAvar(o, model.Generate(seed, 0, n), &s)) << s.message;
  return estimators::CurveFromSummary(s);
}

TEST(CurveCovariances, OnePerShape) {
  CurveCovariances shared;
  const std::vector<Coefficient> terms = {Coefficient::kN, Coefficient::kK};
  const auto a = shared.For(CurveOf(1 << 14, 1), terms);
  ASSERT_NE(a, nullptr);
  EXPECT_EQ(shared.For(CurveOf(1 << 14, 2), terms), a);  // other values, same shape
  EXPECT_NE(shared.For(CurveOf(1 << 13, 1), terms), a);  // another length
  EXPECT_NE(shared.For(CurveOf(1 << 14, 1), {Coefficient::kN}), a);
}

TEST(CurveCovariances, ASharedModelWithMoreTermsGivesTheFitsOwnBits) {
  const estimators::AvarCurve curve = CurveOf(1 << 15, 3);
  CurveCovariances shared;
  for (const std::vector<Coefficient>& terms :
       {std::vector<Coefficient>{Coefficient::kN, Coefficient::kK},
        std::vector<Coefficient>{Coefficient::kQ, Coefficient::kN, Coefficient::kB, Coefficient::kK}}) {
    estimators::FitOptions own;
    own.method = estimators::FitMethod::kGls;
    own.terms = terms;
    estimators::FitOptions with = own;
    with.covariance = shared.For(curve, {Coefficient::kQ, Coefficient::kN, Coefficient::kB, Coefficient::kK,
                                         Coefficient::kR});
    estimators::FitSummary a, b;
    ASSERT_TRUE(estimators::FitAvarModel(own, curve, &a)) << a.message;
    ASSERT_TRUE(estimators::FitAvarModel(with, curve, &b)) << b.message;
    EXPECT_EQ(a.chi2, b.chi2);
    for (Coefficient c : estimators::kAllCoefficients) {
      EXPECT_EQ(a.at(c).value_si, b.at(c).value_si);
      EXPECT_EQ(a.at(c).sigma_si, b.at(c).sigma_si);
      EXPECT_EQ(a.at(c).interval95_si, b.at(c).interval95_si);
      EXPECT_EQ(a.at(c).upper_limit_si, b.at(c).upper_limit_si);
    }
  }
}

}  // namespace
}  // namespace allanlab::experiments::detail
