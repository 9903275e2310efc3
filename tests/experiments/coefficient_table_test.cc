// The coefficient tables' sigma ratio (mean reported sigma / empirical sd) and its standard error,
// checked against the spread of the ratio itself over many independent replicate runs: Gaussian
// errors, and Laplace errors, whose sd scatters sqrt(5/2) times more than a Gaussian one's (the
// error bar must take the errors' fourth moment from the trials, not assume it).
#include "experiments/coefficient_table.h"

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "experiments/coefficient_trial.h"
#include "tests/support/experiment_runs.h"

namespace allanlab::experiments {
namespace {

ColumnStats StatsOf(const std::string& column, const std::vector<double>& values) {
  ColumnStats s;
  s.column = column;
  s.count = static_cast<std::int64_t>(values.size());
  double sum = 0.0;
  for (double v : values) sum += v;
  s.mean = sum / static_cast<double>(s.count);
  double squares = 0.0;
  for (double v : values) squares += (v - s.mean) * (v - s.mean);
  s.std = std::sqrt(squares / static_cast<double>(s.count - 1));
  s.standard_error = s.std / std::sqrt(static_cast<double>(s.count));
  return s;
}

struct RatioSpread {
  double sd_of_ratio = 0.0;    // over the replicates
  double mean_reported = 0.0;  // mean of the rows' sigma_ratio_se
  int replicates = 0;
};

// `replicates` runs of `trials` trials each: relative error = bias + sd * e (e of unit variance,
// Gaussian or Laplace), reported sigma = sd * (1 + 0.1 g).
RatioSpread Replicate(bool laplace, int replicates, int trials, std::uint64_t seed) {
  SweepSpec spec;
  spec.fit_methods = {"gls"};
  spec.confidence_levels = {};
  spec.points.push_back(testing_support::PresetPoint("tg100", 50.0, 600.0, 0));
  const auto compared = ComparedCoefficients(spec, spec.points[0]);
  EXPECT_FALSE(compared.empty());
  const std::string suffix = "/gls/" + std::string(estimators::CoefficientId(compared.front()));

  std::mt19937_64 rng(seed);
  std::normal_distribution<double> gauss;
  std::exponential_distribution<double> expo;
  const double bias = 0.02, sd = 0.1;
  std::vector<double> ratios, reported;
  for (int r = 0; r < replicates; ++r) {
    std::vector<double> err, sq, sigma;
    for (int t = 0; t < trials; ++t) {
      // Laplace of unit variance: (E1 - E2) / sqrt(2).
      const double e = laplace ? (expo(rng) - expo(rng)) / std::sqrt(2.0) : gauss(rng);
      const double x = bias + sd * e;
      err.push_back(x);
      sq.push_back(x * x);
      sigma.push_back(sd * (1.0 + 0.1 * gauss(rng)));
    }
    PointStats ps;
    ps.point = 0;
    ps.trials = trials;
    ps.columns = {StatsOf("rel_err" + suffix, err), StatsOf("sq_rel_err" + suffix, sq),
                  StatsOf("rel_sigma" + suffix, sigma)};
    const std::vector<CoefficientRow> rows = CoefficientRows(spec, {ps});
    for (const CoefficientRow& row : rows) {
      if (row.coefficient != compared.front()) continue;
      ratios.push_back(row.sigma_ratio);
      reported.push_back(row.sigma_ratio_se);
    }
  }
  RatioSpread out;
  out.replicates = static_cast<int>(ratios.size());
  out.sd_of_ratio = StatsOf("ratio", ratios).std;
  out.mean_reported = StatsOf("se", reported).mean;
  return out;
}

// The sd over R replicates has a relative error of about sqrt((kurtosis - 1) / (4 R)) (~1/sqrt(2R)
// for a near-Gaussian ratio); 4 of those, plus 5 % for the delta method's O(1/n) terms at n = 200.
double Tolerance(int replicates) { return 4.0 / std::sqrt(2.0 * replicates) + 0.05; }

TEST(CoefficientTable, SigmaRatioErrorMatchesTheSpreadOfTheRatioForGaussianErrors) {
  const RatioSpread s = Replicate(false, 600, 200, 11);
  ASSERT_EQ(s.replicates, 600);
  EXPECT_NEAR(s.mean_reported / s.sd_of_ratio, 1.0, Tolerance(s.replicates))
      << "reported " << s.mean_reported << ", spread " << s.sd_of_ratio;
}

TEST(CoefficientTable, SigmaRatioErrorFollowsHeavyTailedErrors) {
  const RatioSpread s = Replicate(true, 600, 200, 12);
  ASSERT_EQ(s.replicates, 600);
  EXPECT_NEAR(s.mean_reported / s.sd_of_ratio, 1.0, Tolerance(s.replicates))
      << "reported " << s.mean_reported << ", spread " << s.sd_of_ratio;
  // A Gaussian-only error, sd / sqrt(2 (n - 1)), would be sqrt(2 / 5) of the spread here.
  const double gaussian_only = std::hypot(0.1 / std::sqrt(200.0), 1.0 / std::sqrt(2.0 * 199.0));
  EXPECT_GT(s.mean_reported, 1.15 * gaussian_only);
}

}  // namespace
}  // namespace allanlab::experiments
