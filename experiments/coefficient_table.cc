#include "experiments/coefficient_table.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <set>
#include <sstream>
#include <stdexcept>

#include "common/gnuplot.h"
#include "estimators/tau_grid.h"
#include "experiments/coefficient_trial.h"
#include "experiments/report_files.h"

namespace allanlab::experiments {
namespace {

using estimators::Coefficient;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();


}  // namespace

std::string Cell(double value, int digits) {
  if (std::isnan(value)) return "";
  return SignificantDigits(value, digits);
}

std::string CsvField(const std::string& text) {
  if (text.find_first_of(",\"\n\r") == std::string::npos) return text;
  std::string out = "\"";
  for (char c : text) {
    if (c == '"') out += '"';
    out += c;
  }
  out += "\"";
  return out;
}

std::string DurationText(double seconds) {
  char buffer[32];
  if (seconds < 3600.0) std::snprintf(buffer, sizeof buffer, "%.3g min", seconds / 60.0);
  else std::snprintf(buffer, sizeof buffer, "%.3g h", seconds / 3600.0);
  return buffer;
}

std::vector<CoefficientRow> CoefficientRows(const SweepSpec& spec,
                                            const std::vector<PointStats>& stats) {
  std::vector<CoefficientRow> rows;
  for (const PointStats& ps : stats) {
    if (ps.point < 0 || ps.point >= static_cast<int>(spec.points.size())) continue;
    const SweepPoint& point = spec.points[ps.point];
    const TrueCoefficients truth = TrueCoefficientsOf(point.model);
    for (const std::string& method : MethodsOf(spec)) {
      for (estimators::Coefficient c : ComparedCoefficients(spec, point)) {
        const std::string suffix = "/" + method + "/" + std::string(estimators::CoefficientId(c));
        CoefficientRow r;
        r.point = ps.point;
        r.sensor = point.model.name;
        r.sample_clock = point.model.sample_clock;
        r.samples = point.num_samples;
        r.duration_s = static_cast<double>(point.num_samples) / point.model.sample_clock.rate_hz();
        r.method = method;
        r.coefficient = c;
        r.truth_si = truth.at(c);
        auto mean = [&](const std::string& column, double* se) {
          const ColumnStats* s = ps.Find(column + suffix);
          if (!s || s->count == 0) {
            if (se) *se = kNaN;
            return kNaN;
          }
          if (se) *se = s->standard_error;
          return s->mean;
        };
        const ColumnStats* err = ps.Find("rel_err" + suffix);
        r.n = err ? err->count : 0;
        r.empirical_sd = err && err->count > 1 ? err->std : kNaN;
        r.bias = mean("rel_err", &r.bias_se);
        double mse_se = 0.0;
        const double mse = mean("sq_rel_err", &mse_se);
        r.rmse = std::sqrt(mse);
        r.rmse_se = mse > 0.0 ? mse_se / (2.0 * r.rmse) : kNaN;
        // Trials the runner recorded as failed have no row values at all: count them missing.
        const double missing = mean("missing", nullptr);
        const double trials = static_cast<double>(ps.trials);
        r.failure_rate = trials > 0 ? 1.0 - (std::isnan(missing) ? 0.0 : (1.0 - missing)) *
                                                (trials - static_cast<double>(ps.failed)) / trials
                                    : kNaN;
        double mean_sigma_se = kNaN;
        r.mean_sigma = mean("rel_sigma", &mean_sigma_se);
        r.sigma_ratio = r.mean_sigma / r.empirical_sd;
        const double sd_se = mse_se / (2.0 * r.empirical_sd);
        r.sigma_ratio_se = std::abs(r.sigma_ratio) *
                           std::hypot(mean_sigma_se / r.mean_sigma, sd_se / r.empirical_sd);
        for (double level : spec.confidence_levels) {
          const ColumnStats* s = ps.Find(CoverageColumnName(level) + suffix);
          r.coverage.push_back(s && s->count > 0 ? s->mean : kNaN);
          r.coverage_se.push_back(s && s->count > 0 ? CoverageStandardError(level, s->count) : kNaN);
          const RateInterval wilson = s && s->count > 0 ? WilsonInterval(s->mean, s->count) : RateInterval{kNaN, kNaN};
          r.coverage_low.push_back(wilson.low);
          r.coverage_high.push_back(wilson.high);
        }
        r.read_bias = mean("rel_err_read", &r.read_bias_se);
        rows.push_back(std::move(r));
      }
    }
  }
  return rows;
}

namespace {

const char* MethodColor(const std::string& method) {
  if (method == "slope") return "#d62728";
  if (method == "wls") return "#1f77b4";
  if (method == "log_wls") return "#2ca02c";
  if (method == "default") return "#9467bd";
  return "#111111";  // gls
}

}  // namespace

std::vector<std::pair<std::string, std::string>> CoefficientTrialChoices(const SweepSpec& spec,
                                                                         const RunSummary& run) {
  std::vector<std::pair<std::string, std::string>> f;
  std::set<std::string> sensors;
  for (const SweepPoint& p : spec.points) {
    if (!sensors.insert(p.model.name).second) continue;
    f.emplace_back("sensor " + p.model.name, p.model.description);
  }
  std::ostringstream taus;
  for (const SweepPoint& p : spec.points) {
    FitAveragingWindow window;
    try {
      window = FitWindowOf(spec, p);
    } catch (const std::invalid_argument&) {
      continue;
    }
    const double tau0 = p.model.sample_clock.period_s();
    taus << (taus.tellp() > 0 ? "; " : "") << p.model.name << " " << DurationText(p.num_samples * tau0)
         << " at " << Cell(p.model.sample_clock.rate_hz()) << " Hz: " << Cell(window.min_m * tau0, 3) << " .. "
         << Cell(window.max_m * tau0, 3) << " s";
  }
  std::ostringstream rule;
  if (spec.fit_tau_max_s > 0.0) {
    rule << "fixed by the spec (fit.tau_range " << Cell(spec.fit_tau_min_s, 4) << " .. "
         << Cell(spec.fit_tau_max_s, 4) << " s), the same at every record length; it keeps the "
            "band-limit's white-noise AVAR deficit <= "
         << Cell(kMaxBandLimitDeficit * 100) << " % and <= " << Cell(kMaxBandLimitDeficitInSd)
         << " of the estimate's relative sd at every point (" << taus.str() << ")";
  } else {
    rule << "fits use taus whose white-noise AVAR deficit from the band-limit is <= "
         << Cell(kMaxBandLimitDeficit * 100) << " % and <= " << Cell(kMaxBandLimitDeficitInSd)
         << " of the relative sd sqrt(4m/3N) of a white-noise OAVAR estimate there, up to the "
            "grid's longest ("
         << taus.str() << ")";
  }
  f.emplace_back("fit taus", rule.str());
  f.emplace_back("slope method curve", "the same taus up to m = N/" +
                                           std::to_string(kSlopeMethodMaxFraction) +
                                           " (the plotted diagram)");
  f.emplace_back("term selection", "off: the truth's terms are fitted (spec fit.terms when given)");
  f.emplace_back("errors", "relative to the true coefficient; +- is one Monte Carlo standard error");
  double trial_seconds = 0.0;
  for (const TrialRow& row : run.rows) trial_seconds += row.runtime_s;
  f.emplace_back("cost", Cell(run.wall_time_s, 4) + " s wall, " + Cell(trial_seconds, 4) +
                             " s in trials, " + std::to_string(run.rows.size()) + " trials, " +
                             std::to_string(run.trials_failed) + " failed");
  return f;
}

std::string CoefficientPlotBody(const std::vector<CoefficientRow>& rows, const std::string& sensor,
                                Coefficient c, const std::string& title,
                                const std::vector<GuideLine>& guides) {
  std::vector<std::string> methods;
  for (const CoefficientRow& r : rows) {
    if (r.sensor != sensor || r.coefficient != c) continue;
    if (std::find(methods.begin(), methods.end(), r.method) == methods.end()) methods.push_back(r.method);
  }
  std::ostringstream os;
  os << "set title " << GnuplotQuoted(title) << " noenhanced\n"
     << "set logscale xy\nset format x '%g'\nset format y '%g'\n"
     << "set xlabel 'record length T [h]'\nset ylabel 'relative error of "
     << estimators::CoefficientId(c) << "'\n"
     << "set grid xtics ytics lc rgb '#e8e8e8'\nset key outside right top noenhanced font ',9'\n";
  std::vector<std::string> clauses;
  double x_lo = 1e300, x_hi = 0;
  int block = 0;
  for (const std::string& method : methods) {
    std::ostringstream rmse, bias;
    for (const CoefficientRow& r : rows) {
      if (r.sensor != sensor || r.method != method || r.coefficient != c) continue;
      const double x = r.duration_s / 3600.0;
      x_lo = std::min(x_lo, x);
      x_hi = std::max(x_hi, x);
      if (r.rmse > 0 && std::isfinite(r.rmse)) {
        const double se = std::isfinite(r.rmse_se) ? r.rmse_se : 0.0;
        rmse << Cell(x, 8) << " " << Cell(r.rmse, 8) << " " << Cell(std::max(r.rmse - se, r.rmse * 1e-3), 8)
             << " " << Cell(r.rmse + se, 8) << "\n";
      }
      if (std::abs(r.bias) > 0 && std::isfinite(r.bias)) {
        bias << Cell(x, 8) << " " << Cell(std::abs(r.bias), 8) << "\n";
      }
    }
    const std::string color = MethodColor(method);
    if (rmse.tellp() > 0) {
      os << "$r" << block << " << EOD\n" << rmse.str() << "EOD\n";
      std::ostringstream clause;
      clause << "$r" << block << " using 1:2:3:4 with yerrorlines pt 7 ps 0.8 lw 2 lc rgb '"
             << color << "' title " << GnuplotQuoted(method + " RMSE");
      clauses.push_back(clause.str());
    }
    if (bias.tellp() > 0) {
      os << "$b" << block << " << EOD\n" << bias.str() << "EOD\n";
      std::ostringstream clause;
      clause << "$b" << block << " using 1:2 with linespoints pt 6 ps 0.6 dt 2 lc rgb '" << color
             << "' title " << GnuplotQuoted(method + " |bias|");
      clauses.push_back(clause.str());
    }
    ++block;
  }
  int g = 0;
  for (const GuideLine& line : guides) {
    if (line.sensor != sensor || line.coefficient != c || !(line.anchor_y > 0)) continue;
    std::ostringstream fn;
    fn << "g" << g++;
    os << fn.str() << "(x) = " << Cell(line.anchor_y, 10) << " * (x / " << Cell(line.anchor_x / 3600.0, 10)
       << ")**(" << Cell(line.slope) << ")\n";
    std::ostringstream clause;
    clause << fn.str() << "(x) with lines lw 1 dt 3 lc rgb '#606060' title " << GnuplotQuoted(line.title);
    clauses.push_back(clause.str());
  }
  if (x_hi > 0) os << "set xrange [" << Cell(x_lo / 1.5) << ":" << Cell(x_hi * 1.5) << "]\n";
  if (clauses.empty()) return os.str() + "plot NaN title 'no data'\n";
  os << "plot ";
  for (std::size_t i = 0; i < clauses.size(); ++i) os << (i ? ", \\\n     " : "") << clauses[i];
  os << "\n";
  return os.str();
}

bool RenderCoefficientPlots(const std::vector<CoefficientRow>& rows, const std::string& base,
                            const std::string& title_prefix, const std::vector<GuideLine>& guides,
                            std::string* markdown_images, std::string* why) {
  // The sensor goes into the file name unless the table's name already says it
  // (coefficient_recovery_tg100_N, not coefficient_recovery_tg100_tg100_N).
  std::string table = "_";
  table += base.substr(base.find_last_of('/') + 1);
  table += '_';
  std::set<std::string> done;
  for (const CoefficientRow& r : rows) {
    const std::string id(estimators::CoefficientId(r.coefficient));
    if (!done.insert(r.sensor + "_" + id).second) continue;
    std::string token = "_";
    token += r.sensor;
    token += '_';
    const bool named = table.find(token) != std::string::npos;
    const std::string path = base + "_" + (named ? std::string() : r.sensor + "_") + id;
    const std::string title = title_prefix + ": " + r.sensor + ", " + id;
    if (!RenderGnuplotFigure(CoefficientPlotBody(rows, r.sensor, r.coefficient, title, guides), path,
                             900, 560, why)) {
      return false;
    }
    const std::string file = path.substr(path.find_last_of('/') + 1);
    *markdown_images += "![" + r.sensor + " " + id + "](" + file + ".png)\n";
  }
  return true;
}

bool WriteCoefficientReport(const std::vector<CoefficientRow>& rows, const std::string& base,
                            const std::string& title_prefix, const std::vector<GuideLine>& guides,
                            const std::string& csv, const std::string& markdown, std::string* why) {
  std::string images;
  if (!RenderCoefficientPlots(rows, base, title_prefix, guides, &images, why)) return false;
  return WriteFileAtomically(base + ".csv", csv, why) &&
         WriteFileAtomically(base + ".md", markdown + "\n## Figures\n\n" + images, why);
}

}  // namespace allanlab::experiments
