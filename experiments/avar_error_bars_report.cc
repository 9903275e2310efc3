// The avar_error_bars table: per (noise, estimator, m) bias, empirical vs predicted std and
// coverage, as CSV and Markdown with the same numbers, a headline summary and two figures.
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "estimators/statistic.h"
#include "experiments/avar_error_bars.h"
#include "experiments/report_files.h"

namespace allanlab::experiments {
namespace {

using estimators::Statistic;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kRadPerSToDegPerH = 180.0 / M_PI * 3600.0;
const char* const kKinds[] = {"simple", "gr", "exact"};

struct Coverage {
  double observed = kNaN, se = kNaN;
};

// One table row.
struct Row {
  std::string noise;
  int point = 0;
  std::string estimator;
  bool exact = false;
  std::int64_t m = 0;
  double tau_s = 0.0;
  std::int64_t trials = 0;
  double mean_ratio = kNaN, bias = kNaN, bias_se = kNaN;
  double rel_std = kNaN, rel_std_se = kNaN;
  double edf[3] = {kNaN, kNaN, kNaN};
  double predicted[3] = {kNaN, kNaN, kNaN};  // sqrt(2 / edf)
  double std_over_predicted[3] = {kNaN, kNaN, kNaN};
  std::vector<Coverage> coverage;  // [level][kind], level-major
};

double Mean(const PointStats& stats, const std::string& column) {
  const ColumnStats* c = stats.Find(column);
  return c && c->count > 0 ? c->mean : kNaN;
}

std::string Col(std::string_view q, std::string_view est, std::int64_t m) {
  std::ostringstream out;
  out << q << '/' << est << "/m=" << m;
  return out.str();
}

std::vector<Row> BuildRows(const SweepSpec& spec, const std::vector<PointStats>& stats) {
  std::vector<Row> rows;
  for (const PointStats& ps : stats) {
    const SweepPoint& point = spec.points.at(static_cast<std::size_t>(ps.point));
    const std::string noise = NoiseLabel(point);
    const std::vector<std::int64_t> ms = ErrorBarAveragingFactors(spec, point);
    for (Statistic s : ErrorBarStatistics()) {
      const std::string est(estimators::StatisticId(s));
      for (std::int64_t m : ms) {
        Row row;
        row.noise = noise;
        row.point = ps.point;
        row.estimator = est;
        row.exact = HasExactTheory(s);
        row.m = m;
        row.tau_s = static_cast<double>(m) / point.model.sample_clock.rate_hz();
        const ColumnStats* ratio = ps.Find(Col("ratio", est, m));
        if (ratio && ratio->count > 1) {
          row.trials = ratio->count;
          row.mean_ratio = ratio->mean;
          row.rel_std = row.exact ? ratio->std : ratio->std / ratio->mean;
          if (row.exact) {
            row.bias = ratio->mean - 1.0;
            row.bias_se = ratio->standard_error;
          }
        }
        for (int k = 0; k < 3; ++k) {
          row.edf[k] = Mean(ps, Col(std::string("edf_") + kKinds[k], est, m));
          if (row.edf[k] > 0.0) {
            row.predicted[k] = std::sqrt(2.0 / row.edf[k]);
            row.std_over_predicted[k] = row.rel_std / row.predicted[k];
          }
        }
        // Standard error of a sample std of chi-square-like values (excess kurtosis 12/edf):
        // sd(s)/s ~ sqrt((2 + 12/edf) / n) / 2, with the best EDF available.
        const double edf_best = std::isfinite(row.edf[2]) ? row.edf[2] : row.edf[1];
        if (row.trials > 1 && edf_best > 0.0) {
          row.rel_std_se = row.rel_std * 0.5 *
                           std::sqrt((2.0 + 12.0 / edf_best) / static_cast<double>(row.trials));
        }
        for (double level : spec.confidence_levels) {
          for (const char* kind : kKinds) {
            std::ostringstream name;
            name << "in_ci" << SignificantDigits(100.0 * level, 3) << '/' << kind << '/' << est
                 << "/m=" << m;
            const ColumnStats* c = ps.Find(name.str());
            Coverage cov;
            if (c && c->count > 0) {
              cov.observed = c->mean;
              cov.se = CoverageStandardError(level, c->count);
            }
            row.coverage.push_back(cov);
          }
        }
        rows.push_back(std::move(row));
      }
    }
  }
  return rows;
}

std::string Cell(double v, int digits = 4) { return std::isfinite(v) ? SignificantDigits(v, digits) : "n/a"; }
std::string PlusMinus(double v, double se, int digits = 3) {
  if (!std::isfinite(v)) return "n/a";
  return SignificantDigits(v, digits) + " ± " + SignificantDigits(se, 2);
}

std::string Csv(const SweepSpec& spec, const std::vector<Row>& rows, const std::string& header) {
  std::ostringstream out;
  out << header;
  out << "noise,point,estimator,exact_theory,m,tau_s,trials,mean_ratio,bias,bias_se,rel_std,"
         "rel_std_se,edf_simple,edf_gr_mean,edf_exact,pred_std_simple,pred_std_gr,"
         "pred_std_exact,std_over_simple,std_over_gr,std_over_exact";
  for (double level : spec.confidence_levels) {
    for (const char* kind : kKinds) {
      out << ",coverage" << SignificantDigits(100.0 * level, 3) << '_' << kind << ",coverage"
          << SignificantDigits(100.0 * level, 3) << '_' << kind << "_se";
    }
  }
  out << '\n';
  for (const Row& r : rows) {
    out << '"' << r.noise << "\"," << r.point << ',' << r.estimator << ','
        << (r.exact ? "yes" : "no") << ',' << r.m << ',' << SignificantDigits(r.tau_s, 6) << ','
        << r.trials << ',' << SignificantDigits(r.mean_ratio, 6) << ',' << SignificantDigits(r.bias, 4)
        << ',' << SignificantDigits(r.bias_se, 3) << ',' << SignificantDigits(r.rel_std, 5) << ','
        << SignificantDigits(r.rel_std_se, 3);
    for (double v : r.edf) out << ',' << SignificantDigits(v, 6);
    for (double v : r.predicted) out << ',' << SignificantDigits(v, 5);
    for (double v : r.std_over_predicted) out << ',' << SignificantDigits(v, 4);
    for (const Coverage& c : r.coverage) {
      out << ',' << SignificantDigits(c.observed, 4) << ',' << SignificantDigits(c.se, 3);
    }
    out << '\n';
  }
  return out.str();
}

double Median(std::vector<double> v) {
  v.erase(std::remove_if(v.begin(), v.end(), [](double x) { return !std::isfinite(x); }), v.end());
  if (v.empty()) return kNaN;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

std::string Markdown(const SweepSpec& spec, const std::vector<Row>& rows,
                     const std::string& question, const std::string& provenance) {
  std::ostringstream out;
  out << "# " << spec.name << ": bias and error-bar accuracy of the Allan-family estimators\n\n"
      << question << "\n\n## Provenance\n\n" << provenance << '\n';
  out << "## Headline: empirical std of the estimate / predicted std (median over m)\n\n"
         "A ratio above 1 means the error model is optimistic (its intervals are too short). "
         "Simple = the seed paper's 1/sqrt(2(K-1)) for ADEV (EDF K-1, K = floor(N/m) "
         "clusters); GR = Greenhall-Riley EDF at the identified alpha; exact = 2E^2/Var of the "
         "record's model. Worst coverage = the (observed - nominal) of largest magnitude over "
         "m and both levels.\n\n"
         "| noise | estimator | std/simple | std/GR | std/exact | worst coverage simple | "
         "worst coverage GR | worst coverage exact |\n|---|---|---|---|---|---|---|---|\n";
  for (std::size_t i = 0; i < rows.size();) {
    std::size_t j = i;
    std::vector<double> ratio[3];
    double worst[3] = {kNaN, kNaN, kNaN};
    while (j < rows.size() && rows[j].point == rows[i].point &&
           rows[j].estimator == rows[i].estimator) {
      for (int k = 0; k < 3; ++k) ratio[k].push_back(rows[j].std_over_predicted[k]);
      for (std::size_t l = 0; l < spec.confidence_levels.size(); ++l) {
        for (int k = 0; k < 3; ++k) {
          const double d = rows[j].coverage[l * 3 + k].observed - spec.confidence_levels[l];
          if (std::isfinite(d) && !(std::abs(d) <= std::abs(worst[k]))) worst[k] = d;
        }
      }
      ++j;
    }
    out << "| " << rows[i].noise << " | " << rows[i].estimator;
    for (int k = 0; k < 3; ++k) out << " | " << Cell(Median(ratio[k]), 3);
    for (int k = 0; k < 3; ++k) {
      out << " | ";
      if (!std::isfinite(worst[k])) {
        out << "n/a";
        continue;
      }
      if (worst[k] >= 0) out << '+';
      out << SignificantDigits(worst[k], 2);
    }
    out << " |\n";
    i = j;
  }
  out << "\n## Per averaging factor\n\nbias = mean(AVAR_hat)/E[AVAR_hat] - 1 ± its Monte Carlo "
         "standard error (n/a: sim/ has no exact expectation for this estimator, so no bias "
         "and no coverage are given; its rel. std is std/mean). rel. std = empirical std of "
         "AVAR_hat / E. Coverage = fraction of trials whose chi-square interval contains "
         "E[AVAR_hat] ± binomial standard error.\n";
  int current_point = -1;
  for (const Row& r : rows) {
    if (r.point != current_point) {
      current_point = r.point;
      out << "\n### " << r.noise << "\n\n| estimator | m | tau [s] | trials | bias | rel. std "
             "| std/simple | std/GR | std/exact | EDF simple / GR / exact";
      for (double level : spec.confidence_levels) {
        out << " | cov. " << SignificantDigits(100.0 * level, 3) << "% simple | GR | exact";
      }
      out << " |\n|---|---|---|---|---|---|---|---|---|---";
      for (std::size_t l = 0; l < spec.confidence_levels.size(); ++l) out << "|---|---|---";
      out << "|\n";
    }
    out << "| " << r.estimator << " | " << r.m << " | " << SignificantDigits(r.tau_s, 4) << " | "
        << r.trials << " | " << PlusMinus(r.bias, r.bias_se, 2) << " | "
        << PlusMinus(r.rel_std, r.rel_std_se, 3);
    for (double v : r.std_over_predicted) out << " | " << Cell(v, 3);
    out << " | " << Cell(r.edf[0], 4) << " / " << Cell(r.edf[1], 4) << " / " << Cell(r.edf[2], 4);
    for (const Coverage& c : r.coverage) out << " | " << PlusMinus(c.observed, c.se, 3);
    out << " |\n";
  }
  out << "\nFigures: " << spec.name << "_allan.png/.svg (theory and Monte Carlo band, "
      << "overlapping estimator), " << spec.name << "_coverage.png/.svg (observed vs nominal "
      << "coverage, estimators with exact theory).\n";
  return out.str();
}

std::string AllanFigure(const SweepSpec& spec, const std::vector<Row>& rows) {
  std::ostringstream out;
  const std::size_t panels = spec.points.size();
  const int columns = panels > 4 ? 4 : static_cast<int>(std::max<std::size_t>(panels, 1));
  const int lines = static_cast<int>((panels + columns - 1) / columns);
  for (std::size_t p = 0; p < panels; ++p) {
    const SweepPoint& point = spec.points[p];
    const std::vector<std::int64_t> ms = ErrorBarAveragingFactors(spec, point);
    const std::vector<double> expected = point.model.ExpectedAvar(
        ms, sim::RecordShape{point.num_samples, sim::AvarEstimatorKind::kOverlapping});
    out << "$p" << p << " << EOD\n";
    for (const Row& r : rows) {
      if (r.point != static_cast<int>(p) || r.estimator != "overlapping") continue;
      const auto it = std::find(ms.begin(), ms.end(), r.m);
      const double e = expected[static_cast<std::size_t>(it - ms.begin())];
      const double lo = e * r.mean_ratio * r.mean_ratio / (r.mean_ratio + r.rel_std);
      const double hi = e * (r.mean_ratio + r.rel_std);
      out << SignificantDigits(r.tau_s, 8) << ' ' << SignificantDigits(std::sqrt(e) * kRadPerSToDegPerH, 8)
          << ' ' << SignificantDigits(std::sqrt(e * r.mean_ratio) * kRadPerSToDegPerH, 8) << ' '
          << SignificantDigits(std::sqrt(lo) * kRadPerSToDegPerH, 8) << ' '
          << SignificantDigits(std::sqrt(hi) * kRadPerSToDegPerH, 8) << '\n';
    }
    out << "EOD\n";
  }
  out << "set multiplot layout " << lines << "," << columns << " title "
      << "'" << spec.name << ": OADEV, exact theory vs Monte Carlo mean, band x// (1 + std/mean)'\n"
      << "set logscale xy\nset format y '%g'\nset xlabel 'tau [s]'\nset ylabel 'ADEV [deg/h]'\n"
      << "set key bottom left font ',8'\nset grid\n";
  for (std::size_t p = 0; p < panels; ++p) {
    std::string title = NoiseLabel(spec.points[p]);
    for (char& c : title) {
      if (c == '\'') c = ' ';
    }
    out << "set title '" << title << "' font ',9'\n"
        << "plot $p" << p << " using 1:4:5 with filledcurves lc rgb '#b0c4de' title 'MC mean x// (1 + std/mean)', "
        << "$p" << p << " using 1:2 with lines lw 2 lc rgb 'black' title 'exact theory', "
        << "$p" << p << " using 1:3 with points pt 7 ps 0.6 lc rgb 'red' title 'MC mean'\n";
  }
  out << "unset multiplot\n";
  return out.str();
}

std::string CoverageFigure(const SweepSpec& spec, const std::vector<Row>& rows) {
  std::ostringstream out;
  const double offsets[3] = {-0.012, 0.0, 0.012};
  for (int k = 0; k < 3; ++k) {
    out << "$k" << k << " << EOD\n";
    for (const Row& r : rows) {
      for (std::size_t l = 0; l < spec.confidence_levels.size(); ++l) {
        const Coverage& c = r.coverage[l * 3 + static_cast<std::size_t>(k)];
        if (!std::isfinite(c.observed)) continue;
        out << SignificantDigits(spec.confidence_levels[l] + offsets[k], 6) << ' '
            << SignificantDigits(c.observed, 6) << ' ' << SignificantDigits(c.se, 4) << '\n';
      }
    }
    out << "EOD\n";
  }
  out << "set title '" << spec.name
      << ": coverage of chi-square intervals (each point one noise, estimator and m)'\n"
      << "set xlabel 'nominal coverage'\nset ylabel 'observed coverage'\nset grid\n"
      << "set xrange [0.5:1.0]\nset yrange [0.3:1.02]\nset key bottom right\n"
      << "plot x with lines lc rgb 'black' title 'observed = nominal', "
      << "$k0 using 1:2:3 with yerrorbars pt 7 ps 0.5 lc rgb 'red' title 'simple 1/sqrt(2(K-1))', "
      << "$k1 using 1:2:3 with yerrorbars pt 5 ps 0.5 lc rgb 'blue' title 'Greenhall-Riley EDF', "
      << "$k2 using 1:2:3 with yerrorbars pt 9 ps 0.5 lc rgb 'dark-green' title 'exact EDF'\n";
  return out.str();
}

}  // namespace

std::string AvarErrorBarsExperiment::Question() const {
  return "Question: how biased are the Allan-family estimators on simulated records, and how "
         "well do three error models predict their scatter and the coverage of their "
         "chi-square intervals: (a) the seed paper's / IEEE 952 1/sqrt(2(K-1)) (EDF K-1 with K "
         "non-overlapping clusters), (b) Greenhall-Riley EDF at the identified noise type, (c) "
         "the exact EDF of the simulated record (docs/theory.md §3.1)? Method: `trials` independent "
         "records per noise type; each estimate is divided by its exact expectation "
         "(sim::SensorModel::ExpectedAvar, finite record and band-limit included). Reference: "
         "exact expectations exist in sim/ only for the non-overlapping and overlapping Allan "
         "variance; modified, Hadamard and total variance get no bias and no coverage (marked "
         "n/a), only their relative scatter (std/mean) against the three predictions. The "
         "exact EDF (estimators/exact_edf.h: 2 E^2 / Var, Var = 2 tr((A R)^2) of the "
         "estimator's quadratic form) exists for AVAR, OAVAR, MVAR and OHVAR, not for TOTVAR "
         "(its reflected extension is not a stationary filter); it covers models whose terms "
         "are all Gaussian (none with a ramp or harmonic: n/a), with flicker in its "
         "stationary-increment form (the generator's start-up transient is left out). Pass "
         "criterion: an error model "
         "is right when std/predicted is 1 and coverage equals the nominal level within a few "
         "Monte Carlo standard errors; bias should be 0 within its standard error.";
}

bool AvarErrorBarsExperiment::WriteReport(const SweepSpec& spec, const RunSummary& run,
                                          const std::vector<PointStats>& stats,
                                          const ReportContext& context, std::string* why) const {
  std::vector<Row> rows;
  try {
    rows = BuildRows(spec, stats);
  } catch (const std::exception& e) {
    if (why) *why = std::string("avar_error_bars report: ") + e.what();
    return false;
  }
  std::vector<std::pair<std::string, std::string>> extra = {
      {"estimators", "nonoverlapping, overlapping, modified, hadamard (overlapping), total"},
      {"taus", spec.taus + " (m <= N/4)"},
      {"trials_failed", std::to_string(run.trials_failed)},
  };
  for (const SweepPoint& point : spec.points) {
    extra.emplace_back("point " + std::to_string(point.index),
                       NoiseLabel(point) + ", " + std::to_string(point.num_samples) +
                           " samples at " + SignificantDigits(point.model.sample_clock.rate_hz(), 6) + " Hz");
  }
  const std::string base = context.output_dir + "/" + spec.name;
  const std::string csv = Csv(spec, rows, ProvenanceBlock(spec, context, extra, "# "));
  const std::string md =
      Markdown(spec, rows, Question(), "```\n" + ProvenanceBlock(spec, context, extra, "") + "```\n");
  return WriteFileAtomically(base + ".csv", csv, why) &&
         WriteFileAtomically(base + ".md", md, why) &&
         RenderGnuplotFigure(AllanFigure(spec, rows), base + "_allan", 1400, 700, why) &&
         RenderGnuplotFigure(CoverageFigure(spec, rows), base + "_coverage", 900, 650, why);
}

}  // namespace allanlab::experiments
