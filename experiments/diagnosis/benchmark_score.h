#pragma once
// Scoring of the blind diagnosis benchmark: each recording's diagnosis (read back from
// the JSON `allanlab diagnose` wrote) against the effect it was not told, and the tables:
//   confusion matrix (true effect x verdict), detection and right-effect rates per strength bin,
//   false-alarm rate on controls, the right effect on clearly visible single effects, localization
//   and held-out gap shrinkage, each rate with its Wilson 95 % interval (binomial counts).
// Right effect: the verdict is the true id, or the true id is in also_consistent (the data
// cannot tell it from the verdict); for a control: verdict "none".
// Localization (detected effect recordings whose expected tau range is not empty, benchmark_case.h):
//   overlap: some reported region (any view, on the tau axis; PSD regions at tau = 1/(2 f))
//     intersects the expected range widened by a grid step (10^0.1) either side;
//   contain: one reported region contains the expected range so widened.
// Shrinkage (right diagnoses with a held-out score): chi2 of the second half against the model
// fitted on the first half, baseline / with the effect.
#include <string>
#include <vector>

#include "experiments/diagnosis/benchmark_case.h"

namespace allanlab::experiments {

// What the diagnosis said, as its JSON states it.
struct BenchmarkOutcome {
  bool ok = false;          // diagnose ran and wrote its JSON
  std::string failure;      // otherwise: its error
  bool significant = false;
  double threshold_z = 0.0;
  std::string verdict;      // "none", an id, "a+b", "unexplained"
  std::vector<std::string> also_consistent;
  struct Region {
    std::string view;
    double tau_min_s = 0.0, tau_max_s = 0.0;
  };
  std::vector<Region> regions;
  bool has_heldout = false;  // the verdict's candidate carries held-out before and after
  double heldout_before_chi2 = 0.0, heldout_after_chi2 = 0.0;
  int heldout_points = 0;
};

struct BenchmarkRow {
  // The recording (from BenchmarkCase; the model itself is not kept).
  int index = 0;
  std::string preset;
  double rate_hz = 0.0;
  std::int64_t num_samples = 0;
  std::string truth;          // effect id or "control"
  std::string params;         // "name=value;..." (SI, names of effect.h)
  double target_z = 0.0, strength_z = 0.0, oavar_z = 0.0, kurtosis_z = 0.0, halves_z = 0.0;
  double relative_peak = 0.0, peak_tau_s = 0.0;
  std::string strength_class;
  double expected_tau_min_s = 0.0, expected_tau_max_s = 0.0;  // 0: none expected
  BenchmarkOutcome outcome;
  // Scores.
  bool detected = false;  // significant gap
  bool right = false;     // see above
  int overlap = -1, contain = -1;  // localization: 1 yes, 0 no, -1 not applicable
  double shrink = 0.0;    // held-out chi2 before / after (0: not applicable)
  // The held-out chi2 after is within the model's own 95 % range (chi2 quantile on its points):
  // the half is as the model predicts, so a ratio short of 5 only says the gap was small.
  bool heldout_at_model_level = false;
};

// The row of a drawn case and its diagnosis, scored.
BenchmarkRow ScoreBenchmarkCase(const BenchmarkCase& c, const BenchmarkOutcome& outcome);

// The diagnosis names `id`: the verdict is it, holds it as a member of a set ("a+b"), or lists
// it in also_consistent.
bool NamesEffect(const BenchmarkOutcome& outcome, const std::string& id);

// The verdict's column in the confusion matrix: "none", an id, "pair" or "unexplained"
// ("failed" when diagnose did not run).
std::string VerdictColumn(const BenchmarkOutcome& outcome);

struct Proportion {
  int successes = 0, trials = 0;
  double rate() const { return trials > 0 ? static_cast<double>(successes) / trials : 0.0; }
  double low = 0.0, high = 1.0;  // Wilson score interval, 95 %
};
Proportion MakeProportion(int successes, int trials);

struct StrengthBin {
  double lo = 0.0, hi = 0.0;
  Proportion detected, right;
};

struct BenchmarkSummary {
  std::vector<std::string> truths;    // row labels: "control", then the ids of the effects drawn
  std::vector<std::string> not_drawn;  // effect ids no recording holds (no row, no rate)
  std::vector<std::string> verdicts;  // column labels
  std::vector<std::vector<int>> confusion;
  Proportion false_alarm;             // controls with a significant gap
  Proportion control_none;            // controls with verdict none
  Proportion clear_right;             // clear single effects, right effect
  std::vector<std::pair<std::string, Proportion>> clear_right_by_effect;
  std::vector<StrengthBin> bins;      // effect recordings by strength
  Proportion overlap, contain;
  int shrink_count = 0;
  double shrink_median = 0.0, shrink_min = 0.0;
  Proportion shrink_5x;
  Proportion shrink_5x_or_model_level;
  int failures = 0;
};
BenchmarkSummary SummarizeBenchmark(const std::vector<BenchmarkRow>& rows);

}  // namespace allanlab::experiments
