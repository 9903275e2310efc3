// The seed_paper driver on a short TG-100 record against the exact OAVAR expectation, the truth
// helpers against docs/theory.md §4.2, and its report's files.
#include "experiments/seed_paper.h"

#include <cmath>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "estimators/confidence.h"
#include "sim/sensor_spec.h"
#include "tests/experiments/experiment_test_support.h"
#include "tests/support/monte_carlo.h"
#include "tests/support/read_file.h"

namespace allanlab::experiments {
namespace {

using testing_support::kZ;

constexpr double kRadPerSToDegPerH = 180.0 / M_PI * 3600.0;

SweepSpec PresetSpec(const char* preset, std::int64_t samples, std::int64_t trials) {
  SweepSpec spec;
  spec.name = "seed_paper_test";
  spec.driver = "seed_paper";
  spec.seed = 7;
  spec.trials = trials;
  spec.taus = "dense:10";
  SweepPoint point;
  std::string why;
  EXPECT_TRUE(sim::LoadPreset(preset, &point.model, &why)) << why;
  point.num_samples = samples;
  spec.points.push_back(point);
  spec.canonical_text = "name: seed_paper_test";
  return spec;
}

TEST(SeedPaperTruth, PresetsAndTheFloorFormula) {
  sim::SensorModel mg25, tg100;
  std::string why;
  ASSERT_TRUE(sim::LoadPreset("mg25_mems", &mg25, &why)) << why;
  ASSERT_TRUE(sim::LoadPreset("tg100", &tg100, &why)) << why;
  const SeedPaperTruth a = TruthOf(mg25), b = TruthOf(tg100);
  EXPECT_NEAR(a.n_deg_per_sqrt_h, 0.0267, 1e-9);
  EXPECT_NEAR(a.b_deg_per_h, 0.1806, 1e-9);
  EXPECT_NEAR(a.k_deg_per_h_per_sqrt_h, 0.03, 1e-9);
  EXPECT_NEAR(a.cutoff_hz, 100.0, 1e-12);
  // docs/theory.md §4.2: B_read = sqrt(B^2 + 2.617 N K) in datasheet units (consistent: deg^2/h^2).
  EXPECT_NEAR(a.b_floor_deg_per_h, std::sqrt(0.1806 * 0.1806 + 2.617 * 0.0267 * 0.03), 2e-5);
  EXPECT_NEAR(b.n_deg_per_sqrt_h, 0.0183, 1e-9);
  EXPECT_NEAR(b.b_floor_deg_per_h, 0.8731, 1e-9);  // no RRW: the floor is B itself
}

TEST(SeedPaperDriver, ReadingsAgreeWithTheExactCurveAndTheReportIsWritten) {
  constexpr std::int64_t kTrials = 24;
  constexpr std::int64_t kSamples = 240000;  // 10 min at 400 Hz
  const SweepSpec spec = PresetSpec("tg100", kSamples, kTrials);
  const SweepPoint& point = spec.points[0];
  SeedPaperExperiment experiment;
  const testing_support::DriverRun run =
      testing_support::RunTrials(experiment.Driver(), spec, point, kTrials);

  const std::vector<std::int64_t> ms = SeedPaperAveragingFactors(spec, point);
  ASSERT_NE(std::find(ms.begin(), ms.end(), 400), ms.end());  // tau = 1 s is on the grid
  const double expected =
      point.model.ExpectedAvar(400, sim::RecordShape{kSamples, sim::AvarEstimatorKind::kOverlapping});
  const std::vector<double> ratio = run.Column("ratio/overlapping/m=400");
  const std::vector<double> n_curve = run.Column("N_curve/paper");
  ASSERT_EQ(ratio.size(), static_cast<std::size_t>(kTrials));
  double mean = 0.0;
  for (std::size_t t = 0; t < ratio.size(); ++t) {
    // N off the curve is sigma(1 s)/60 of the same estimate.
    const double sigma_1s = n_curve[t] * 60.0;
    EXPECT_NEAR(sigma_1s * sigma_1s / (expected * kRadPerSToDegPerH * kRadPerSToDegPerH), ratio[t],
                1e-9);
    mean += ratio[t] / kTrials;
  }
  // Unbiased within z SD/sqrt(trials), SD = sqrt(2/edf) with the white-noise GR EDF at 1 s.
  const double edf = estimators::StatisticEdf(estimators::Statistic::kAllanOverlapping, 0, 400,
                                              kSamples, 1.0 / 400.0);
  EXPECT_NEAR(mean, 1.0, kZ * std::sqrt(2.0 / edf / kTrials));
  // The white level dominates at 1 s, so the reading is N within a few per cent (flicker adds
  // 0.4413 B^2 = 0.336 (deg/h)^2 to sigma(1 s)^2 = 1.21: ~13 % in variance, ~7 % in N).
  const SeedPaperTruth truth = TruthOf(point.model);
  const double n_expected = std::sqrt(expected) * kRadPerSToDegPerH / 60.0;
  EXPECT_GT(n_expected / truth.n_deg_per_sqrt_h, 1.0);

  const testing_support::ScratchDirectory scratch("allanlab_seed_paper_test");
  const std::string dir = scratch.path();
  ReportContext context;
  context.output_dir = dir;
  context.git_sha = "abc1234";
  context.build_type = "Release";
  context.command_line = "allanlab sweep experiments/specs/seed_paper.yaml";
  context.date_utc = "2026-11-22T00:00:00Z";
  RunSummary summary;
  summary.ok = true;
  std::string why;
  ASSERT_TRUE(experiment.WriteReport(spec, summary, {testing_support::Stats(run, 0)}, context, &why))
      << why;
  for (const char* ext : {".csv", ".md", "_allan.png", "_allan.svg", "_coverage.png", "_coverage.svg"}) {
    EXPECT_TRUE(std::filesystem::exists(dir + "/seed_paper_test" + std::string(ext))) << ext;
  }
  for (const char* ext : {".csv", ".md"}) {
    const std::string text = testing_support::ReadAll(dir + "/seed_paper_test" + std::string(ext));
    EXPECT_NE(text.find("git_sha: abc1234"), std::string::npos) << ext;
    EXPECT_NE(text.find("command: allanlab sweep experiments/specs/seed_paper.yaml"),
              std::string::npos) << ext;
    EXPECT_NE(text.find("tg100"), std::string::npos) << ext;
  }
  // The paper's printed numbers, recomputed: 1.6/60 = 0.02667 (printed 0.0035), 0.58/0.6643.
  const std::string md = testing_support::ReadAll(dir + "/seed_paper_test.md");
  EXPECT_NE(md.find("| mg25_mems | 1.6 | 0.02667 | 0.0035 |"), std::string::npos);
  EXPECT_NE(md.find("| tg100 | 1.1 | 0.01833 | 0.055 | 0.58 | 0.8731 | 0.88 |"), std::string::npos);
}

}  // namespace
}  // namespace allanlab::experiments
