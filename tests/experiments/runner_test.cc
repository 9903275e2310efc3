#include "experiments/runner.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <numeric>
#include <stdexcept>
#include <string>

#include "experiments/aggregate.h"

namespace allanlab::experiments {
namespace {

// A short record per trial and a few numbers from it; trial 5 of point 1 fails.
class TinyDriver : public TrialDriver {
 public:
  std::vector<std::string> Columns(const SweepSpec&, const SweepPoint& point) const override {
    std::vector<std::string> columns = {"mean", "var", "first"};
    if (point.index == 1) columns.push_back("extra");
    return columns;
  }
  std::unique_ptr<TrialWorkspace> MakeWorkspace() const override {
    return std::make_unique<TrialWorkspace>();
  }
  std::vector<double> Run(const SweepSpec& spec, const SweepPoint& point, std::int64_t trial,
                          TrialWorkspace*) const override {
    if (point.index == 1 && trial == 5) throw std::runtime_error("no luck");
    const std::vector<double> y =
        point.model.Generate(PointSeed(spec.seed, point.index), static_cast<std::uint64_t>(trial),
                             point.num_samples);
    const double mean = std::accumulate(y.begin(), y.end(), 0.0) / static_cast<double>(y.size());
    double var = 0.0;
    for (double v : y) var += (v - mean) * (v - mean);
    std::vector<double> out = {mean, var / static_cast<double>(y.size() - 1), y[0]};
    if (point.index == 1) out.push_back(trial == 3 ? std::nan("") : 1.0);
    return out;
  }
};

SweepSpec Spec() {
  SweepSpec spec;
  std::string why;
  const bool ok = LoadSweepSpecYaml(R"(
name: tiny
driver: avar_bias
seed: 99
trials: 37
sensor: {model: {name: m, sample_rate: 100 Hz, terms: [{type: arw, N: 1 deg/sqrt(h)}, {type: bias_instability, B: 1 deg/h}]}}
record: {samples: 500}
sweep: {parameters: [{path: 'sensor.terms[0].N', values: [1 deg/sqrt(h), 2 deg/sqrt(h), 3 deg/sqrt(h)]}]}
)", "tiny", &spec, &why);
  EXPECT_TRUE(ok) << why;
  return spec;
}

RunSummary RunTiny(const RunnerOptions& options) {
  RunSummary summary;
  TinyDriver driver;
  EXPECT_TRUE(RunSweep(Spec(), driver, options, &summary)) << summary.message;
  return summary;
}

void ExpectSameRows(const RunSummary& a, const RunSummary& b) {
  ASSERT_EQ(a.rows.size(), b.rows.size());
  EXPECT_EQ(a.columns, b.columns);
  for (std::size_t i = 0; i < a.rows.size(); ++i) {
    EXPECT_EQ(a.rows[i].point, b.rows[i].point);
    EXPECT_EQ(a.rows[i].trial, b.rows[i].trial);
    EXPECT_EQ(a.rows[i].status, b.rows[i].status);
    ASSERT_EQ(a.rows[i].values.size(), b.rows[i].values.size());
    // Bit-identical, NaN included.
    EXPECT_EQ(0, std::memcmp(a.rows[i].values.data(), b.rows[i].values.data(),
                             a.rows[i].values.size() * sizeof(double)))
        << "row " << i;
  }
}

std::string TempPath(const std::string& name) {
  return ::testing::TempDir() + "/" + name + "." + std::to_string(::getpid());
}

TEST(Runner, RowsAreInPointTrialOrderWithFailuresKept) {
  RunnerOptions options;
  options.threads = 2;
  const RunSummary s = RunTiny(options);
  ASSERT_TRUE(s.ok);
  ASSERT_EQ(s.rows.size(), 3u * 37u);
  for (std::size_t i = 0; i < s.rows.size(); ++i) {
    EXPECT_EQ(s.rows[i].point, static_cast<int>(i / 37));
    EXPECT_EQ(s.rows[i].trial, static_cast<std::int64_t>(i % 37));
  }
  EXPECT_EQ(s.trials_failed, 1);
  const TrialRow& failed = s.rows[37 + 5];
  EXPECT_FALSE(failed.ok);
  EXPECT_EQ(failed.status, "failed: no luck");
  ASSERT_EQ(failed.values.size(), 4u);
  EXPECT_TRUE(std::isnan(failed.values[0]));
  EXPECT_EQ(s.columns[1].size(), 4u);
}

TEST(Runner, BitIdenticalForThreadsAndBatchSizes) {
  RunnerOptions one;
  one.threads = 1;
  one.batch_trials = 64;
  const RunSummary reference = RunTiny(one);
  for (int threads : {1, 2, 3}) {
    for (std::int64_t batch : {1, 5, 1000}) {
      RunnerOptions options;
      options.threads = threads;
      options.batch_trials = batch;
      SCOPED_TRACE("threads " + std::to_string(threads) + " batch " + std::to_string(batch));
      ExpectSameRows(reference, RunTiny(options));
    }
  }
}

TEST(Runner, AggregateSkipsFailedAndNonFiniteAndSumsInTrialOrder) {
  RunnerOptions options;
  const RunSummary s = RunTiny(options);
  const std::vector<PointStats> stats = Aggregate(s);
  ASSERT_EQ(stats.size(), 3u);
  EXPECT_EQ(stats[1].trials, 37);
  EXPECT_EQ(stats[1].failed, 1);
  const ColumnStats* extra = stats[1].Find("extra");
  ASSERT_NE(extra, nullptr);
  EXPECT_EQ(extra->count, 35);  // one failed trial, one NaN
  EXPECT_EQ(extra->mean, 1.0);
  EXPECT_EQ(extra->std, 0.0);
  EXPECT_EQ(stats[1].Find("nope"), nullptr);
  // Direct two-pass check of the first column of point 0.
  double sum = 0.0;
  for (int t = 0; t < 37; ++t) sum += s.rows[static_cast<std::size_t>(t)].values[0];
  const double mean = sum / 37.0;
  double ss = 0.0;
  for (int t = 0; t < 37; ++t) {
    const double d = s.rows[static_cast<std::size_t>(t)].values[0] - mean;
    ss += d * d;
  }
  const ColumnStats* c = stats[0].Find("mean");
  EXPECT_NEAR(c->mean, mean, 1e-12 * std::abs(mean) + 1e-15);
  EXPECT_NEAR(c->std, std::sqrt(ss / 36.0), 1e-9 * std::sqrt(ss / 36.0));
  EXPECT_NEAR(c->standard_error, c->std / std::sqrt(37.0), 1e-15);
  EXPECT_NEAR(CoverageStandardError(0.95, 400), std::sqrt(0.95 * 0.05 / 400), 1e-15);
}

TEST(Runner, ResumeFromAPartialCheckpointIsIdentical) {
  RunnerOptions plain;
  plain.threads = 2;
  const RunSummary reference = RunTiny(plain);

  const std::string path = TempPath("runner_resume.ckpt");
  std::remove(path.c_str());
  RunnerOptions options;
  options.threads = 2;
  options.batch_trials = 4;
  options.checkpoint_path = path;
  const RunSummary full = RunTiny(options);
  ExpectSameRows(reference, full);
  // Without --resume an existing store is not overwritten.
  {
    RunSummary again;
    TinyDriver driver;
    EXPECT_FALSE(RunSweep(Spec(), driver, options, &again));
    EXPECT_NE(again.message.find("--resume"), std::string::npos) << again.message;
  }
  // Cut the store in the middle of a record (a torn write), then resume.
  std::ifstream in(path, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  in.close();
  const std::size_t cut = bytes.size() * 2 / 5;
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(cut));
  }
  options.resume = true;
  const RunSummary resumed = RunTiny(options);
  EXPECT_GT(resumed.trials_resumed, 0);
  EXPECT_LT(resumed.trials_resumed, 3 * 37);
  ExpectSameRows(reference, resumed);
  // Everything is now in the store: a second resume computes nothing.
  const RunSummary all = RunTiny(options);
  EXPECT_EQ(all.trials_resumed, 3 * 37);
  ExpectSameRows(reference, all);
  std::remove(path.c_str());
}

TEST(Runner, ResumeRefusesAnotherSpec) {
  const std::string path = TempPath("runner_other.ckpt");
  std::remove(path.c_str());
  RunnerOptions options;
  options.checkpoint_path = path;
  RunTiny(options);
  SweepSpec other = Spec();
  other.seed = 100;
  other.canonical_text += "changed";
  options.resume = true;
  RunSummary s;
  TinyDriver driver;
  EXPECT_FALSE(RunSweep(other, driver, options, &s));
  EXPECT_NE(s.message.find("another sweep"), std::string::npos) << s.message;
  std::remove(path.c_str());
}

TEST(Runner, InvalidOptions) {
  RunnerOptions options;
  std::string why;
  options.batch_trials = 0;
  EXPECT_FALSE(options.IsValid(&why));
  options.batch_trials = 1;
  options.resume = true;
  EXPECT_FALSE(options.IsValid(&why));
  EXPECT_NE(why.find("checkpoint"), std::string::npos);
}

}  // namespace
}  // namespace allanlab::experiments
