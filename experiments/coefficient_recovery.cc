#include "experiments/coefficient_recovery.h"

#include <cmath>
#include <set>
#include <sstream>

#include "experiments/coefficient_table.h"
#include "experiments/report_files.h"

namespace allanlab::experiments {
namespace {

std::string PlusMinus(double value, double se, int digits = 3) {
  if (std::isnan(value)) return "";
  if (std::isnan(se)) return Cell(value, digits);
  return Cell(value, digits) + " +- " + Cell(se, 2);
}

std::string Percent(double level) { return Cell(level * 100.0, 4) + " %"; }

}  // namespace

std::string CoefficientRecoveryExperiment::Question() const {
  return "How well do the slope method, WLS, log-WLS and GLS recover the IEEE 952 coefficients "
         "(Q, N, B, K, R present in the model) of a simulated sensor, and does their error shrink "
         "with the record length? Method: per trial, simulate the record, take its overlapping "
         "Allan curve (octave taus), fit it with each method (terms of the truth, no term "
         "selection) and compare with the true coefficients; per point: relative bias and RMSE "
         "with Monte Carlo standard errors, reported vs empirical sigma, coverage of the reported "
         "68.3 % and 95 % intervals (binomial errors), failure rate. Reference: the simulated "
         "truth (B: the Kasdin flicker coefficient; for the slope method's B also what the curve "
         "minimum estimates, sqrt(B^2 + 2.617 N K), docs/theory.md §4.2). Read: a consistent method's "
         "RMSE falls with T and its coverage is nominal within ~2 binomial errors; where terms "
         "overlap the slope method has an error floor that a longer record does not lower "
         "(docs/theory.md §4.5).";
}

bool CoefficientRecoveryExperiment::WriteReport(const SweepSpec& spec, const RunSummary& run,
                                                const std::vector<PointStats>& stats,
                                                const ReportContext& context,
                                                std::string* why) const {
  const std::vector<CoefficientRow> rows = CoefficientRows(spec, stats);
  const auto choices = CoefficientTrialChoices(spec, run);

  std::vector<std::string> header = {"sensor", "T", "T_s", "sample_rate_hz", "samples", "method",
                                     "coefficient", "truth", "unit", "n", "failure_rate",
                                     "bias", "bias_se", "rmse", "rmse_se", "empirical_sd",
                                     "mean_reported_sigma", "sigma_ratio", "sigma_ratio_se"};
  for (double level : spec.confidence_levels) {
    header.push_back("coverage" + Cell(level * 100, 4));
    header.push_back("coverage" + Cell(level * 100, 4) + "_se");
    header.push_back("coverage" + Cell(level * 100, 4) + "_wilson95_low");
    header.push_back("coverage" + Cell(level * 100, 4) + "_wilson95_high");
  }
  header.push_back("bias_vs_minimum_reading");
  header.push_back("bias_vs_minimum_reading_se");

  std::ostringstream csv;
  csv << ProvenanceBlock(spec, context, choices, "# ");
  for (std::size_t i = 0; i < header.size(); ++i) csv << (i ? "," : "") << header[i];
  csv << "\n";
  for (const CoefficientRow& r : rows) {
    const auto c = r.coefficient;
    csv << CsvField(r.sensor) << "," << DurationText(r.duration_s) << "," << Cell(r.duration_s) << ","
        << Cell(r.sample_clock.rate_hz()) << "," << r.samples << "," << r.method << ","
        << estimators::CoefficientId(c) << "," << Cell(estimators::ToDatasheetUnit(c, r.truth_si)) << ","
        << CsvField(std::string(estimators::DatasheetUnit(c))) << "," << r.n << ","
        << Cell(r.failure_rate) << "," << Cell(r.bias) << "," << Cell(r.bias_se) << ","
        << Cell(r.rmse) << "," << Cell(r.rmse_se) << "," << Cell(r.empirical_sd) << ","
        << Cell(r.mean_sigma) << "," << Cell(r.sigma_ratio) << "," << Cell(r.sigma_ratio_se);
    for (std::size_t k = 0; k < r.coverage.size(); ++k) {
      csv << "," << Cell(r.coverage[k]) << "," << Cell(r.coverage_se[k]) << "," << Cell(r.coverage_low[k])
          << "," << Cell(r.coverage_high[k]);
    }
    csv << "," << Cell(r.read_bias) << "," << Cell(r.read_bias_se) << "\n";
  }

  std::ostringstream md;
  md << "# " << spec.name << "\n\n" << Question() << "\n\n## Provenance\n\n"
     << ProvenanceBlock(spec, context, choices, "    ")
     << "\nErrors are relative (estimate / truth - 1); +- is one Monte Carlo standard error. "
        "sigma ratio = mean reported sigma / empirical sd (1 = honest error bars), +- its standard "
        "error (delta method: the mean sigma's and the sd's, the latter from the squared errors' "
        "spread). A coefficient "
        "a fit leaves at zero counts as -1 (-100 %). Coverage: share of trials whose interval holds "
        "the truth, +- its binomial error at the nominal level, [Wilson 95 % interval]. The default "
        "method's intervals are profile-likelihood ones (68.3 %: chi2 + 1, 95 %: chi2 + 3.84); "
        "the others' are estimate +- z sigma.\n";
  std::set<std::string> seen;
  for (const CoefficientRow& first : rows) {
    if (!seen.insert(first.sensor).second) continue;
    md << "\n## " << first.sensor << "\n\n| T | method | coef | truth | n | fail | bias | RMSE | "
          "emp. sd | mean sigma | sigma ratio |";
    for (double level : spec.confidence_levels) md << " cover " << Percent(level) << " |";
    md << " B bias vs sqrt(B^2+2.617NK) |\n|";
    for (std::size_t i = 0; i < 12 + spec.confidence_levels.size(); ++i) md << "---|";
    md << "\n";
    for (const CoefficientRow& r : rows) {
      if (r.sensor != first.sensor) continue;
      const auto c = r.coefficient;
      md << "| " << DurationText(r.duration_s) << " | " << r.method << " | "
         << estimators::CoefficientId(c) << " | " << Cell(estimators::ToDatasheetUnit(c, r.truth_si), 4)
         << " " << estimators::DatasheetUnit(c) << " | " << r.n << " | " << Cell(r.failure_rate, 3)
         << " | " << PlusMinus(r.bias, r.bias_se) << " | " << PlusMinus(r.rmse, r.rmse_se) << " | "
         << Cell(r.empirical_sd, 3) << " | " << Cell(r.mean_sigma, 3) << " | "
         << PlusMinus(r.sigma_ratio, r.sigma_ratio_se) << " |";
      for (std::size_t k = 0; k < r.coverage.size(); ++k) {
        md << " " << PlusMinus(r.coverage[k], r.coverage_se[k]);
        if (!std::isnan(r.coverage_low[k])) {
          md << " [" << Cell(r.coverage_low[k], 3) << ", " << Cell(r.coverage_high[k], 3) << "]";
        }
        md << " |";
      }
      md << " " << PlusMinus(r.read_bias, r.read_bias_se) << " |\n";
    }
  }

  // The consistent-estimator slope T^-1/2 through GLS's RMSE at the shortest T.
  std::vector<GuideLine> guides;
  for (const CoefficientRow& r : rows) {
    if (r.method != "gls" || !(r.rmse > 0)) continue;
    bool have = false;
    for (const GuideLine& g : guides) have = have || (g.sensor == r.sensor && g.coefficient == r.coefficient);
    if (!have) guides.push_back({r.sensor, r.coefficient, -0.5, r.duration_s, r.rmse, "T^-1/2"});
  }
  return WriteCoefficientReport(rows, context.output_dir + "/" + spec.name,
                                spec.name + " (relative RMSE and |bias| vs T)", guides, csv.str(), md.str(), why);
}

}  // namespace allanlab::experiments
