// record_length: the theory slopes, the weighted log-log line, a small sweep of T through the
// driver (fixed seed) against the T^-1/2 law, and the report's files.
#include "experiments/record_length.h"

#include <cmath>
#include <stdexcept>
#include <unistd.h>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "experiments/aggregate.h"
#include "experiments/coefficient_table.h"
#include "sim/sensor_spec.h"
#include "tests/support/experiment_runs.h"
#include "tests/support/monte_carlo.h"

namespace allanlab::experiments {
namespace {

using estimators::Coefficient;
using testing_support::PresetPoint;
using testing_support::RunSweepInline;

TEST(RecordLength, AFixedTauRangeIsTheSameAtEveryLengthAndHonoursTheBandLimit) {
  SweepSpec spec;
  spec.taus = "octave";
  spec.fit_tau_min_s = 2.56;
  spec.fit_tau_max_s = 40.96;
  for (double seconds : {600.0, 86400.0}) {
    const SweepPoint p = PresetPoint("tg100", 50.0, seconds, 0);
    const FitAveragingWindow w = FitWindowOf(spec, p);
    EXPECT_EQ(w.min_m, 128) << seconds;  // 2.56 s at 50 Hz
    EXPECT_EQ(w.max_m, 2048) << seconds;
  }
  // Without a fixed range the shortest tau grows with T (the band-limit rule): the old design.
  SweepSpec growing;
  growing.taus = "octave";
  EXPECT_LT(FitWindowOf(growing, PresetPoint("tg100", 50.0, 600.0, 0)).min_m,
            FitWindowOf(growing, PresetPoint("tg100", 50.0, 86400.0, 0)).min_m);
  // A range starting below what the band-limit allows on 24 h, or leaving < 8 clusters, is refused.
  spec.fit_tau_min_s = 0.32;
  EXPECT_THROW(FitWindowOf(spec, PresetPoint("tg100", 50.0, 86400.0, 0)), std::invalid_argument);
  spec.fit_tau_min_s = 2.56;
  spec.fit_tau_max_s = 163.84;
  EXPECT_THROW(FitWindowOf(spec, PresetPoint("tg100", 50.0, 600.0, 0)), std::invalid_argument);
}

TEST(RecordLength, FitLineRecoversAnExactLineAndScalesItsErrorByTheScatter) {
  LogLogSlope line;
  ASSERT_TRUE(FitLine({0, 1, 2, 3}, {1, 0.5, 0, -0.5}, {0.1, 0.1, 0.1, 0.1}, &line));
  EXPECT_NEAR(line.slope, -0.5, 1e-12);
  EXPECT_NEAR(line.intercept, 1.0, 1e-12);
  EXPECT_NEAR(line.chi2, 0.0, 1e-20);
  EXPECT_NEAR(line.slope_se, 0.1 / std::sqrt(5.0), 1e-12);  // sigma / sqrt(sum (x - xbar)^2)
  ASSERT_TRUE(FitLine({0, 1, 2, 3}, {0, 1, 1, 0}, {0.1, 0.1, 0.1, 0.1}, &line));
  EXPECT_GT(line.chi2, 2.0);
  EXPECT_GT(line.slope_se, 0.1 / std::sqrt(5.0));
  EXPECT_FALSE(FitLine({1}, {1}, {1}, &line));
}

SweepSpec TwoLengths() {
  SweepSpec spec;
  spec.name = "record_length_small";
  spec.driver = "record_length";
  spec.seed = 20261123;
  spec.trials = 40;
  spec.fit_methods = {"slope", "gls"};
  spec.fit_tau_min_s = 0.64;   // the same fitted taus at both lengths
  spec.fit_tau_max_s = 10.24;
  spec.points.push_back(PresetPoint("tg100", 50.0, 150.0, 0));
  spec.points.push_back(PresetPoint("tg100", 50.0, 2400.0, 1));
  return spec;
}

TEST(RecordLength, GlsErrorOfNShrinksAsTheSquareRootOfT) {
  const SweepSpec spec = TwoLengths();
  RecordLengthExperiment experiment;
  const std::vector<CoefficientRow> rows =
      CoefficientRows(spec, Aggregate(RunSweepInline(spec, experiment.Driver())));
  std::vector<double> x, y, sigma;
  for (const CoefficientRow& r : rows) {
    if (r.method != "gls" || r.coefficient != Coefficient::kN) continue;
    EXPECT_EQ(r.failure_rate, 0.0);
    x.push_back(std::log(r.duration_s));
    y.push_back(std::log(r.rmse));
    sigma.push_back(r.rmse_se / r.rmse);
  }
  ASSERT_EQ(x.size(), 2u);
  LogLogSlope line;
  ASSERT_TRUE(FitLine(x, y, sigma, &line));
  // The same taus (0.64 .. 10.24 s) at both lengths, EDF ~ T/tau: slope -1/2.
  EXPECT_LE(std::abs(line.slope + 0.5), testing_support::kZ * line.slope_se)
      << "slope " << line.slope << " +- " << line.slope_se;
  EXPECT_LT(line.slope_se, 0.15);
}

TEST(RecordLength, ReportWritesCsvMarkdownAndPlotsWithProvenance) {
  SweepSpec spec = TwoLengths();
  spec.trials = 4;
  RecordLengthExperiment experiment;
  const RunSummary run = RunSweepInline(spec, experiment.Driver());
  ReportContext context;
  std::filesystem::path output_dir = std::filesystem::temp_directory_path() / "allanlab_record_length_test_";
  output_dir += std::to_string(::getpid());  // two suites at once must not share it
  context.output_dir = output_dir.string();
  std::filesystem::remove_all(context.output_dir);
  context.git_sha = "def5678";
  context.build_type = "Release";
  context.command_line = "allanlab sweep experiments/specs/record_length.yaml";
  context.date_utc = "2026-11-22T00:00:00Z";
  std::string why;
  ASSERT_TRUE(experiment.WriteReport(spec, run, Aggregate(run), context, &why)) << why;
  for (const char* ext : {".csv", ".md"}) {
    std::ifstream in(context.output_dir + "/" + spec.name + ext);
    ASSERT_TRUE(in.good()) << ext;
    std::stringstream text;
    text << in.rdbuf();
    for (const char* needle : {"def5678", "Release", "20261123", "record_length.yaml", "tg100",
                               "gls", "slope"}) {
      EXPECT_NE(text.str().find(needle), std::string::npos) << ext << " lacks " << needle;
    }
  }
  for (const char* ext : {".png", ".svg"}) {
    EXPECT_GT(std::filesystem::file_size(context.output_dir + "/" + spec.name + "_tg100_N" + ext), 0u);
  }
  std::filesystem::remove_all(context.output_dir);
}

}  // namespace
}  // namespace allanlab::experiments
