// diagnose's default baseline is what `allanlab fit` reports: on a band-limited record it holds the
// cutoff fit finds and refits the IEEE terms with it, choosing them as fit does (AIC over the
// subsets, linear_profile.h). Records from independent/ (a generator written apart from sim/ and
// the fit): N, B and K behind a second-order 20 Hz low-pass (bilinear, 8x oversampled) at 100 Hz,
// 1 h, no quantization and no rate ramp.
// What it catches: the refit with the cutoff held kept every term (no choice), so Q and R, absent
// from the records, came out as values with a sigma several times larger ("R 0.1246 +- 2.033
// deg/h^2") where fit gives their 95 % upper limits.
#include <gtest/gtest.h>

#include <cstdint>
#include <string>

#include "estimators/fit/fit_model.h"
#include "experiments/diagnosis/baseline.h"
#include "independent/generate.h"
#include "independent/recipe.h"

#include "tests/support/independent_recipes.h"

namespace allanlab::experiments {
namespace {

TEST(DiagnoseBaseline, ChoosesItsTermsAsFitDoes) {
  const independent::Recipe r = testing_support::BandLimitedMemsRecipe();
  const SampleClock clock = SampleClock::FromRateHz(r.rate_hz);
  int band_limited = 0, limits = 0;
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    estimators::AvarCurve curve;
    std::string why, note;
    ASSERT_TRUE(RecordCurve(independent::Generate(r, 360000, seed, 0), clock, &curve, &why)) << why;
    estimators::ModelFitOptions fit_options;  // `allanlab fit`'s defaults
    fit_options.band_limit = estimators::BandLimitPolicy::kAuto;
    estimators::ModelFitSummary fitted;
    ASSERT_TRUE(estimators::FitModel(fit_options, curve, &fitted)) << fitted.fit.message;
    DiagnoseOptions options;
    options.baseline = DiagnoseOptions::Baseline::kFit;
    detail::BaselineSpec spec;
    estimators::FitSummary baseline;
    ASSERT_TRUE(detail::FitBaseline(options, curve, &spec, &baseline, &note, &why)) << why;
    band_limited += fitted.band_limited;
    for (estimators::Coefficient c : estimators::kAllCoefficients) {
      const std::string id(estimators::CoefficientId(c));
      const estimators::CoefficientEstimate &b = baseline.at(c), &f = fitted.fit.at(c);
      EXPECT_EQ(b.fitted, f.fitted) << "seed " << seed << ": " << id << " in the baseline and in fit";
      if (b.fitted) continue;
      ++limits;
      EXPECT_TRUE(b.has_upper_limit) << "seed " << seed << ": " << id;
      EXPECT_GT(b.upper_limit_si, 0.0) << "seed " << seed << ": " << id;
    }
  }
  EXPECT_EQ(band_limited, 4) << "the records do not test the held band-limit";
  EXPECT_GE(limits, 4) << "Q and R are absent from every record: fit gives them by their upper limits";
}

}  // namespace
}  // namespace allanlab::experiments
