#include "experiments/record_length.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>

#include "estimators/tau_grid.h"
#include "experiments/aggregate.h"
#include "experiments/coefficient_table.h"
#include "experiments/report_files.h"

namespace allanlab::experiments {
namespace {

using estimators::Coefficient;

std::string Slope(double value) {
  if (std::isnan(value)) return "";
  return Cell(value, 3);
}

// The fitted tau window of a point, as text ("0.64 .. 80 s").
std::string WindowText(const SweepSpec& spec, const SweepPoint& p) {
  const FitAveragingWindow w = FitWindowOf(spec, p);
  const double tau0 = p.model.sample_clock.period_s();
  return Cell(w.min_m * tau0, 3) + " .. " + Cell(w.max_m * tau0, 3) + " s";
}

}  // namespace

bool FitLine(const std::vector<double>& x, const std::vector<double>& y,
             const std::vector<double>& sigma, LogLogSlope* line) {
  double s = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  int n = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (!std::isfinite(x[i]) || !std::isfinite(y[i]) || !(sigma[i] > 0) || !std::isfinite(sigma[i])) continue;
    const double w = 1.0 / (sigma[i] * sigma[i]);
    s += w;
    sx += w * x[i];
    sy += w * y[i];
    sxx += w * x[i] * x[i];
    sxy += w * x[i] * y[i];
    ++n;
  }
  const double delta = s * sxx - sx * sx;
  if (n < 2 || !(delta > 0)) return false;
  line->points = n;
  line->slope = (s * sxy - sx * sy) / delta;
  line->intercept = (sxx * sy - sx * sxy) / delta;
  line->chi2 = 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (!std::isfinite(x[i]) || !std::isfinite(y[i]) || !(sigma[i] > 0) || !std::isfinite(sigma[i])) continue;
    const double r = (y[i] - line->intercept - line->slope * x[i]) / sigma[i];
    line->chi2 += r * r;
  }
  line->dof = n - 2;
  double variance = s / delta;
  if (line->dof >= 1 && line->chi2 > line->dof) variance *= line->chi2 / line->dof;
  line->slope_se = std::sqrt(variance);
  return true;
}

std::string RecordLengthExperiment::Question() const {
  return "How does the error of each IEEE 952 coefficient shrink with the record length T, per "
         "method (slope, WLS, log-WLS, GLS)? Method: the coefficient_recovery trials on a sweep "
         "of T; per sensor, method and coefficient a weighted least-squares line through "
         "ln(relative RMSE) vs ln T over the lengths where the coefficient is identifiable "
         "(relative RMSE <= 0.3), its error scaled by sqrt(chi2/dof) when the points scatter more "
         "than their errors. With a fixed tau range (fit.tau_range) T changes only the number of "
         "clusters at each fitted tau, so a consistent fit's error goes as T^-1/2 (EDF ~ T/tau, "
         "docs/theory.md §3.2): reference slope -1/2, met when the slope's 95 % interval lies "
         "within -1/2 +- 0.1. Without one the fitted taus grow with T and the slope also holds the "
         "effect of the moved tau range (no reference; compare with the fixed-range table).";
}

bool RecordLengthExperiment::WriteReport(const SweepSpec& spec, const RunSummary& run,
                                         const std::vector<PointStats>& stats,
                                         const ReportContext& context, std::string* why) const {
  const std::vector<CoefficientRow> rows = CoefficientRows(spec, stats);
  const auto choices = CoefficientTrialChoices(spec, run);
  const bool fixed = spec.fit_tau_max_s > 0.0;
  constexpr double kReference = -0.5;

  struct Line {
    std::string sensor, method;
    Coefficient coefficient;
    LogLogSlope fit;
    bool ok = false;
    int lengths = 0, identifiable = 0;
    double t_lo = 0, t_hi = 0, rmse_lo = 0, rmse_hi = 0;  // over the identifiable lengths
    double rmse_lo_se = 0, rmse_hi_se = 0;
    std::string window_lo, window_hi;                    // fitted taus at t_lo, t_hi
    RateInterval slope95{std::nan(""), std::nan("")};
    std::string verdict;
  };
  std::vector<Line> lines;
  std::set<std::string> seen_keys;
  for (const CoefficientRow& first : rows) {
    const std::string key = first.sensor + "|" + first.method + "|" +
                            std::string(estimators::CoefficientId(first.coefficient));
    if (!seen_keys.insert(key).second) continue;
    Line line;
    line.sensor = first.sensor;
    line.method = first.method;
    line.coefficient = first.coefficient;
    std::vector<double> x, y, sigma;
    line.t_lo = 1e300;
    for (const CoefficientRow& r : rows) {
      if (r.sensor != first.sensor || r.method != first.method || r.coefficient != first.coefficient) continue;
      ++line.lengths;
      if (!(r.rmse <= kIdentifiableRmse) || r.failure_rate > 0.5) continue;
      ++line.identifiable;
      x.push_back(std::log(r.duration_s));
      y.push_back(std::log(r.rmse));
      sigma.push_back(r.rmse_se / r.rmse);
      const SweepPoint& p = spec.points[r.point];
      if (r.duration_s < line.t_lo) {
        line.t_lo = r.duration_s;
        line.rmse_lo = r.rmse;
        line.rmse_lo_se = r.rmse_se;
        line.window_lo = WindowText(spec, p);
      }
      if (r.duration_s > line.t_hi) {
        line.t_hi = r.duration_s;
        line.rmse_hi = r.rmse;
        line.rmse_hi_se = r.rmse_se;
        line.window_hi = WindowText(spec, p);
      }
    }
    line.ok = line.identifiable >= 3 && FitLine(x, y, sigma, &line.fit);
    if (line.ok) {
      line.slope95 = {line.fit.slope - 1.96 * line.fit.slope_se, line.fit.slope + 1.96 * line.fit.slope_se};
      if (fixed) line.verdict = TargetVerdict(line.slope95, kReference - kSlopeTolerance, kReference + kSlopeTolerance);
    } else {
      line.verdict = line.identifiable == 0 ? "not identifiable" : "identifiable at < 3 lengths";
    }
    lines.push_back(line);
  }

  std::ostringstream csv;
  csv << ProvenanceBlock(spec, context, choices, "# ")
      << "sensor,method,coefficient,lengths,identifiable_lengths,T_min_s,T_max_s,taus_at_T_min,"
         "taus_at_T_max,slope,slope_se,slope_low95,slope_high95,chi2,dof,reference_slope,verdict,"
         "rmse_at_T_min,rmse_at_T_max\n";
  for (const Line& l : lines) {
    const bool has = l.identifiable > 0;
    csv << CsvField(l.sensor) << "," << l.method << "," << estimators::CoefficientId(l.coefficient)
        << "," << l.lengths << "," << l.identifiable << "," << (has ? Cell(l.t_lo) : "") << ","
        << (has ? Cell(l.t_hi) : "") << "," << CsvField(l.window_lo) << "," << CsvField(l.window_hi)
        << "," << (l.ok ? Cell(l.fit.slope) : "") << "," << (l.ok ? Cell(l.fit.slope_se) : "") << ","
        << (l.ok ? Cell(l.slope95.low) : "") << "," << (l.ok ? Cell(l.slope95.high) : "") << ","
        << (l.ok ? Cell(l.fit.chi2) : "") << "," << (l.ok ? std::to_string(l.fit.dof) : "") << ","
        << (fixed ? Cell(kReference) : "") << "," << CsvField(l.verdict) << ","
        << (has ? Cell(l.rmse_lo) : "") << "," << (has ? Cell(l.rmse_hi) : "") << "\n";
  }

  std::ostringstream md;
  md << "# " << spec.name << "\n\n" << Question() << "\n\n## Provenance\n\n"
     << ProvenanceBlock(spec, context, choices, "    ")
     << "\nRMSE is relative (of estimate / truth - 1). slope = d ln RMSE / d ln T +- its standard "
        "error [95 % interval] (RMSE ± its Monte Carlo standard error), over the record lengths where the coefficient is identifiable "
        "(relative RMSE <= "
     << Cell(kIdentifiableRmse) << "; a slope needs 3 of them). "
     << (fixed ? "The fitted taus are the same at every T (fit.tau_range): reference -1/2; met "
                 "when the 95 % interval lies within -1/2 +- " + Cell(kSlopeTolerance) +
                     ", not met when it lies outside, else undecided.\n"
               : "The fitted taus grow with T (columns 'taus'): the slope holds both the extra "
                 "clusters and the moved tau range, so no reference slope is printed; the table "
                 "of the same sensor at a fixed tau range separates the two.\n");
  std::set<std::string> sensors;
  for (const Line& first : lines) {
    if (!sensors.insert(first.sensor).second) continue;
    md << "\n## " << first.sensor << "\n\n| method | coef | identifiable at | T | taus (shortest T) "
          "| taus (longest T) | RMSE (shortest T) | RMSE (longest T) | slope [95 %] | chi2 / dof |"
       << (fixed ? " verdict (-1/2 +- " + Cell(kSlopeTolerance) + ") |" : "") << "\n"
       << "|---|---|---|---|---|---|---|---|---|---|" << (fixed ? "---|" : "") << "\n";
    for (const Line& l : lines) {
      if (l.sensor != first.sensor) continue;
      const bool has = l.identifiable > 0;
      md << "| " << l.method << " | " << estimators::CoefficientId(l.coefficient) << " | "
         << l.identifiable << " of " << l.lengths << " | "
         << (has ? DurationText(l.t_lo) + " .. " + DurationText(l.t_hi) : "") << " | "
         << l.window_lo << " | " << l.window_hi << " | "
         << (has ? Cell(l.rmse_lo, 3) + " ± " + Cell(l.rmse_lo_se, 2) : "") << " | "
         << (has ? Cell(l.rmse_hi, 3) + " ± " + Cell(l.rmse_hi_se, 2) : "") << " | "
         << (l.ok ? Slope(l.fit.slope) + " +- " + Cell(l.fit.slope_se, 2) + " [" +
                        Cell(l.slope95.low, 3) + ", " + Cell(l.slope95.high, 3) + "]"
                  : (l.identifiable == 0 ? "not identifiable" : "too few lengths"))
         << " | "
         << (l.ok && l.fit.dof > 0 ? Cell(l.fit.chi2, 3) + " / " + std::to_string(l.fit.dof) : "")
         << " |" << (fixed ? " " + (l.ok ? l.verdict : std::string()) + " |" : "") << "\n";
    }
  }

  // The T^-1/2 reference through GLS's RMSE at the shortest identifiable T (fixed taus only).
  std::vector<GuideLine> guides;
  for (const Line& l : lines) {
    if (!fixed || l.method != "gls" || !l.ok) continue;
    guides.push_back({l.sensor, l.coefficient, kReference, l.t_lo, l.rmse_lo, "T^-1/2"});
  }
  return WriteCoefficientReport(rows, context.output_dir + "/" + spec.name,
                                spec.name + (fixed ? " (T^-1/2 through GLS)" : ""), guides, csv.str(),
                                md.str(), why);
}

}  // namespace allanlab::experiments
