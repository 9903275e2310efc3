// The avar_error_bars driver against closed-form white-noise theory (docs/theory.md §3.2), and its
// report's files.
#include "experiments/avar_error_bars.h"

#include <cmath>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "tests/experiments/experiment_test_support.h"
#include "sim/units.h"
#include "tests/support/monte_carlo.h"
#include "tests/support/read_file.h"

namespace allanlab::experiments {
namespace {

using testing_support::kZ;

SweepSpec WhiteSpec(std::int64_t trials) {
  SweepSpec spec;
  spec.name = "avar_error_bars_test";
  spec.driver = "avar_error_bars";
  spec.seed = 20261122;
  spec.trials = trials;
  spec.taus = "octave";
  SweepPoint point;
  point.index = 0;
  point.model.sample_clock = SampleClock::FromRateHz(100.0);
  point.model.terms.push_back(sim::WhiteRateNoise{.arw_rad_per_sqrt_s = 1e-3});
  point.num_samples = 1024;
  spec.points.push_back(point);
  spec.canonical_text = "test spec\nsecond line";
  return spec;
}

std::string Col(const char* q, const char* est, std::int64_t m) {
  return std::string(q) + "/" + est + "/m=" + std::to_string(m);
}

double Mean(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v) s += x;
  return s / static_cast<double>(v.size());
}
double Variance(const std::vector<double>& v) {
  const double mean = Mean(v);
  double s = 0.0;
  for (double x : v) s += (x - mean) * (x - mean);
  return s / static_cast<double>(v.size() - 1);
}

class AvarErrorBarsTest : public ::testing::Test {
 protected:
  static constexpr std::int64_t kTrials = 2000;
  static void SetUpTestSuite() {
    spec_ = new SweepSpec(WhiteSpec(kTrials));
    run_ = new testing_support::DriverRun(
        testing_support::RunTrials(experiment_.Driver(), *spec_, spec_->points[0], kTrials));
  }
  static void TearDownTestSuite() {
    delete spec_;
    delete run_;
  }
  static inline AvarErrorBarsExperiment experiment_;
  static inline SweepSpec* spec_ = nullptr;
  static inline testing_support::DriverRun* run_ = nullptr;
};

TEST_F(AvarErrorBarsTest, RowsHaveTheDeclaredColumnsAndGrid) {
  ASSERT_EQ(run_->rows.size(), static_cast<std::size_t>(kTrials));
  for (const auto& row : run_->rows) ASSERT_EQ(row.size(), run_->columns.size());
  // Octave grid up to N/4 = 256.
  EXPECT_EQ(ErrorBarAveragingFactors(*spec_, spec_->points[0]),
            (std::vector<std::int64_t>{1, 2, 4, 8, 16, 32, 64, 128, 256}));
  EXPECT_EQ(NoiseLabel(spec_->points[0]), "white (N)");
}

// EDF constants: K - 1 and the exact non-overlapping white-noise EDF 2(M-1)^2/(3M-4).
TEST_F(AvarErrorBarsTest, EdfConstantsMatchClosedForms) {
  for (std::int64_t m : {1, 4, 16, 64, 256}) {
    const double clusters = static_cast<double>(1024 / m);
    EXPECT_EQ(run_->Column(Col("edf_simple", "nonoverlapping", m))[0], clusters - 1.0) << m;
    EXPECT_NEAR(run_->Column(Col("edf_exact", "nonoverlapping", m))[0],
                2.0 * (clusters - 1) * (clusters - 1) / (3 * clusters - 4),
                1e-9 * clusters) << m;
    // No exact EDF for the total variance (reflected extension): NaN, so the table says n/a.
    EXPECT_TRUE(std::isnan(run_->Column(Col("edf_exact", "total", m))[0])) << m;
  }
}

// Mean ratio = 1 within z SD/sqrt(trials), SD from the exact EDF (AVAR_hat/E has variance 2/edf).
TEST_F(AvarErrorBarsTest, RatiosAreUnbiased) {
  for (const char* est : {"nonoverlapping", "overlapping"}) {
    for (std::int64_t m : {1, 4, 16, 64, 256}) {
      const double edf = run_->Column(Col("edf_exact", est, m))[0];
      const double tolerance = kZ * std::sqrt(2.0 / edf / kTrials);
      EXPECT_NEAR(Mean(run_->Column(Col("ratio", est, m))), 1.0, tolerance) << est << " m=" << m;
    }
  }
}

// The scatter matches the exact EDF and, for non-overlapping white noise, exceeds the simple
// formula's by the factor 1.5 in variance (docs/theory.md §3.3). SE of a sample variance of
// chi-square-like values: sqrt(2/n + 12/(edf n)) relative.
TEST_F(AvarErrorBarsTest, ScatterMatchesExactEdfNotTheSimpleFormula) {
  for (std::int64_t m : {4, 16}) {
    const double edf = run_->Column(Col("edf_exact", "nonoverlapping", m))[0];
    const double simple = run_->Column(Col("edf_simple", "nonoverlapping", m))[0];
    const double variance = Variance(run_->Column(Col("ratio", "nonoverlapping", m)));
    const double relative_se = std::sqrt(2.0 / kTrials + 12.0 / (edf * kTrials));
    EXPECT_NEAR(variance / (2.0 / edf), 1.0, kZ * relative_se) << m;
    EXPECT_GT(variance / (2.0 / simple), 1.0 + kZ * relative_se) << "simple formula not optimistic, m=" << m;
  }
}

// The modified and Hadamard estimators have an exact EDF too: their relative scatter (the ratio
// is normalised by E[OAVAR], so divide by its mean) matches 2/edf.
TEST_F(AvarErrorBarsTest, ModifiedAndHadamardScatterMatchesTheirExactEdf) {
  for (const char* est : {"modified", "hadamard"}) {
    for (std::int64_t m : {1, 4, 16, 64}) {
      const double edf = run_->Column(Col("edf_exact", est, m))[0];
      ASSERT_GT(edf, 0.0) << est << " m=" << m;
      const std::vector<double> ratio = run_->Column(Col("ratio", est, m));
      const double rel_variance = Variance(ratio) / (Mean(ratio) * Mean(ratio));
      const double relative_se = std::sqrt(2.0 / kTrials + 12.0 / (edf * kTrials));
      EXPECT_NEAR(rel_variance / (2.0 / edf), 1.0, kZ * relative_se) << est << " m=" << m;
    }
  }
}

// Intervals from the exact EDF cover at their nominal rate within z binomial errors.
TEST_F(AvarErrorBarsTest, ExactEdfIntervalsCoverAtTheNominalRate) {
  for (const char* est : {"nonoverlapping", "overlapping"}) {
    for (std::int64_t m : {1, 4, 16, 64}) {
      for (auto [level, key] : {std::pair{0.683, "in_ci68.3"}, std::pair{0.95, "in_ci95"}}) {
        const double coverage = Mean(run_->Column(std::string(key) + "/exact/" + est + "/m=" + std::to_string(m)));
        EXPECT_NEAR(coverage, level, kZ * CoverageStandardError(level, kTrials))
            << est << " m=" << m << " level " << level;
      }
    }
  }
}

TEST_F(AvarErrorBarsTest, ReportWritesCsvMarkdownAndPlotsWithProvenance) {
  const testing_support::ScratchDirectory scratch("allanlab_avar_error_bars_test");
  const std::string dir = scratch.path();
  ReportContext context;
  context.output_dir = dir;
  context.git_sha = "abc1234";
  context.build_type = "Release";
  context.command_line = "allanlab sweep experiments/specs/avar_error_bars.yaml";
  context.date_utc = "2026-11-22T00:00:00Z";
  RunSummary run;
  run.ok = true;
  const std::vector<PointStats> stats = {testing_support::Stats(*run_, 0)};
  std::string why;
  ASSERT_TRUE(experiment_.WriteReport(*spec_, run, stats, context, &why)) << why;
  for (const char* ext : {".csv", ".md", "_allan.png", "_allan.svg", "_coverage.png", "_coverage.svg"}) {
    EXPECT_TRUE(std::filesystem::exists(dir + "/avar_error_bars_test" + std::string(ext))) << ext;
  }
  for (const char* ext : {".csv", ".md"}) {
    const std::string text = testing_support::ReadAll(dir + "/avar_error_bars_test" + std::string(ext));
    EXPECT_NE(text.find("git_sha: abc1234"), std::string::npos) << ext;
    EXPECT_NE(text.find("build_type: Release"), std::string::npos) << ext;
    EXPECT_NE(text.find("seed: 20261122"), std::string::npos) << ext;
    EXPECT_NE(text.find("command: allanlab sweep experiments/specs/avar_error_bars.yaml"),
              std::string::npos) << ext;
    EXPECT_NE(text.find("white (N)"), std::string::npos) << ext;
  }
  // No temporaries left behind.
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    EXPECT_EQ(entry.path().string().find(".tmp."), std::string::npos) << entry.path();
  }
}

}  // namespace
}  // namespace allanlab::experiments
