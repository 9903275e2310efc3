#include "experiments/record_length.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>

#include "estimators/tau_grid.h"
#include "experiments/coefficient_table.h"
#include "experiments/report_files.h"

namespace allanlab::experiments {
namespace {

using estimators::Coefficient;

// Log-log slope of each coefficient's IEEE 952 AVAR shape (Q tau^-2 ... R tau^2).
double Exponent(Coefficient c) { return static_cast<double>(static_cast<int>(c)) - 2.0; }

double TermAvar(const TrueCoefficients& truth, Coefficient c, double tau) {
  const double v = truth.at(c);
  return v * v * estimators::AsymptoteShape(c, tau);
}

// The present term with the largest asymptotic AVAR at tau.
Coefficient Dominant(const TrueCoefficients& truth, double tau) {
  Coefficient best = Coefficient::kN;
  double best_value = -1.0;
  for (Coefficient c : estimators::kAllCoefficients) {
    if (!truth.has(c)) continue;
    const double v = TermAvar(truth, c, tau);
    if (v > best_value) {
      best_value = v;
      best = c;
    }
  }
  return best;
}

double FitTauMin(const SweepSpec& spec, const SweepPoint& p) {
  estimators::TauGridOptions grid;
  std::string why;
  if (!estimators::TauGridOptions::Parse(spec.taus, &grid, &why)) return 1.0 / p.sample_rate_hz;
  const double tau0 = 1.0 / p.sample_rate_hz;
  return tau0 * static_cast<double>(SmallestFitAveragingFactor(
                    p.model, p.sample_rate_hz, p.num_samples,
                    estimators::CandidateAveragingFactors(grid, tau0, p.num_samples / 2)));
}

std::string Slope(double value) {
  if (std::isnan(value)) return "";
  return Cell(value, 3);
}

}  // namespace

double PredictedErrorSlope(const TrueCoefficients& truth, Coefficient c, double tau_min_s,
                           double tau_max_s) {
  if (!truth.has(c) || !(tau_max_s > tau_min_s)) return -0.5;
  // Dominant somewhere on a fine log grid of the fitted taus: its own EDF ~ T/tau decides.
  const int steps = 64;
  for (int i = 0; i <= steps; ++i) {
    const double tau = tau_min_s * std::pow(tau_max_s / tau_min_s, static_cast<double>(i) / steps);
    if (Dominant(truth, tau) == c) return -0.5;
  }
  // Short-tau terms are read at tau_min, whose EDF ~ T/tau_min: still T^-1/2.
  const Coefficient d = Dominant(truth, tau_max_s);
  const double mu = Exponent(c), nu = Exponent(d);
  if (mu <= nu) return -0.5;
  return -(mu - nu);
}

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
         "method (slope, WLS, log-WLS, GLS), and does it follow the theory? Method: the "
         "coefficient_recovery trials on a sweep of T; per sensor, method and coefficient a "
         "weighted least-squares line through ln(relative RMSE) vs ln T (weights from the Monte "
         "Carlo error of each RMSE; its error scaled by sqrt(chi2/dof) when the points scatter "
         "more than their errors). Reference: a coefficient read where its own term dominates has "
         "a relative error ~ 1/sqrt(EDF), EDF ~ T/tau (docs/theory.md §3.2): slope -1/2 (Q, N always; "
         "B, K once their region is inside the record); a long-tau term that never dominates "
         "(AVAR ~ tau^mu under a dominant tau^nu) is a perturbation at the longest taus whose "
         "relative error goes as T^-(mu-nu): -1 for B under white noise or K under flicker. A "
         "method with a bias floor (the slope method where terms overlap, docs/theory.md §4.5) "
         "flattens towards 0. Read: the fits' slopes should match the theory within ~2 standard "
         "errors.";
}

bool RecordLengthExperiment::WriteReport(const SweepSpec& spec, const RunSummary& run,
                                         const std::vector<PointStats>& stats,
                                         const ReportContext& context, std::string* why) const {
  const std::vector<CoefficientRow> rows = CoefficientRows(spec, stats);
  const auto choices = CoefficientTrialChoices(spec, run);

  struct Line {
    std::string sensor, method;
    Coefficient coefficient;
    LogLogSlope fit;
    bool ok = false;
    double t_lo = 0, t_hi = 0, rmse_lo = 0, rmse_hi = 0, theory_lo = 0, theory_hi = 0;
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
      x.push_back(std::log(r.duration_s));
      y.push_back(std::log(r.rmse));
      sigma.push_back(r.rmse_se / r.rmse);
      const SweepPoint& p = spec.points[r.point];
      const double theory = PredictedErrorSlope(TrueCoefficientsOf(p.model), r.coefficient,
                                                FitTauMin(spec, p), r.duration_s / 4.0);
      if (r.duration_s < line.t_lo) {
        line.t_lo = r.duration_s;
        line.rmse_lo = r.rmse;
        line.theory_lo = theory;
      }
      if (r.duration_s > line.t_hi) {
        line.t_hi = r.duration_s;
        line.rmse_hi = r.rmse;
        line.theory_hi = theory;
      }
    }
    line.ok = FitLine(x, y, sigma, &line.fit);
    lines.push_back(line);
  }

  std::ostringstream csv;
  csv << ProvenanceBlock(spec, context, choices, "# ")
      << "sensor,method,coefficient,T_min_s,T_max_s,points,slope,slope_se,chi2,dof,"
         "theory_slope_at_T_min,theory_slope_at_T_max,rmse_at_T_min,rmse_at_T_max\n";
  for (const Line& l : lines) {
    csv << CsvField(l.sensor) << "," << l.method << "," << estimators::CoefficientId(l.coefficient)
        << "," << Cell(l.t_lo) << "," << Cell(l.t_hi) << "," << (l.ok ? l.fit.points : 0) << ","
        << (l.ok ? Cell(l.fit.slope) : "") << "," << (l.ok ? Cell(l.fit.slope_se) : "") << ","
        << (l.ok ? Cell(l.fit.chi2) : "") << "," << (l.ok ? std::to_string(l.fit.dof) : "") << ","
        << Cell(l.theory_lo) << "," << Cell(l.theory_hi) << "," << Cell(l.rmse_lo) << ","
        << Cell(l.rmse_hi) << "\n";
  }

  std::ostringstream md;
  md << "# " << spec.name << "\n\n" << Question() << "\n\n## Provenance\n\n"
     << ProvenanceBlock(spec, context, choices, "    ")
     << "\nRMSE is relative (of estimate / truth - 1). slope = d ln RMSE / d ln T +- its standard "
        "error; theory at the shortest and the longest T (they differ where a term's region "
        "enters the record).\n";
  std::set<std::string> sensors;
  for (const Line& first : lines) {
    if (!sensors.insert(first.sensor).second) continue;
    md << "\n## " << first.sensor << "\n\n| method | coef | T | RMSE (shortest T) | RMSE (longest "
          "T) | slope | chi2 / dof | theory (shortest T) | theory (longest T) |\n"
          "|---|---|---|---|---|---|---|---|---|\n";
    for (const Line& l : lines) {
      if (l.sensor != first.sensor) continue;
      md << "| " << l.method << " | " << estimators::CoefficientId(l.coefficient) << " | "
         << DurationText(l.t_lo) << " .. " << DurationText(l.t_hi) << " | " << Cell(l.rmse_lo, 3)
         << " | " << Cell(l.rmse_hi, 3) << " | "
         << (l.ok ? Slope(l.fit.slope) + " +- " + Cell(l.fit.slope_se, 2) : "") << " | "
         << (l.ok && l.fit.dof > 0 ? Cell(l.fit.chi2, 3) + " / " + std::to_string(l.fit.dof) : "")
         << " | " << Slope(l.theory_lo) << " | " << Slope(l.theory_hi) << " |\n";
    }
  }

  // Theory slopes through GLS's RMSE at the shortest and the longest T.
  std::vector<GuideLine> guides;
  for (const Line& l : lines) {
    if (l.method != "gls") continue;
    guides.push_back({l.sensor, l.coefficient, l.theory_lo, l.t_lo, l.rmse_lo,
                      "theory T^" + Cell(l.theory_lo, 3)});
    if (l.theory_hi != l.theory_lo) {
      guides.push_back({l.sensor, l.coefficient, l.theory_hi, l.t_hi, l.rmse_hi,
                        "theory T^" + Cell(l.theory_hi, 3)});
    }
  }
  return WriteCoefficientReport(rows, context.output_dir + "/" + spec.name,
                                spec.name + " (theory slopes through GLS)", guides, csv.str(), md.str(), why);
}

}  // namespace allanlab::experiments
