// The seed_paper table: per simulated gyro, what the paper's procedure reads vs the truth,
// with the paper's printed numbers checked, as CSV and Markdown plus two figures.
#include <cmath>
#include <limits>
#include <sstream>

#include "experiments/aggregate.h"
#include "experiments/report_files.h"
#include "experiments/seed_paper.h"

namespace allanlab::experiments {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kRadPerSToDegPerH = 180.0 / M_PI * 3600.0;
const double kFloorFactor = std::sqrt(2.0 * std::log(2.0) / M_PI);

// What the paper prints for each gyro (Mikheev et al. 2021, text under Figs. 2 and 3).
struct PaperNumbers {
  const char* preset;
  double sigma_1s_deg_per_h, n_printed, sigma_bias_deg_per_h, b_printed, bandwidth_hz;
};
constexpr PaperNumbers kPaper[] = {
    {"mg25_mems", 1.6, 0.0035, 0.12, 0.18, 100.0},
    {"tg100", 1.1, 0.055, 0.58, 0.88, 100.0},
};
const PaperNumbers* PaperFor(const std::string& name) {
  for (const PaperNumbers& p : kPaper) {
    if (name == p.preset || name.rfind(std::string(p.preset) + "_", 0) == 0) return &p;
  }
  return nullptr;
}

struct Quantity {
  const char* column;
  const char* label;
  const char* unit;
};
constexpr Quantity kQuantities[] = {
    {"N_curve/paper", "N = sigma(1 s)/60 off the curve", "deg/sqrt(h)"},
    {"N_line/slope", "N from the -1/2 line", "deg/sqrt(h)"},
    {"sigma_min/curve", "sigma_min (floor, dense overlapping ADEV to N/2)", "deg/h"},
    {"tau_min/curve", "tau of the minimum", "s"},
    {"B_min/paper", "B = sigma_min/0.6643 (dense overlapping ADEV to N/2)", "deg/h"},
    {"fc_first_order/inflection", "bandwidth 0.301/tau_peak", "Hz"},
    {"fc_paper_rule/inflection", "bandwidth 1/(2 pi tau_peak) (paper's rule)", "Hz"},
    {"peak_tau/inflection", "tau of the short-tau ADEV maximum", "s"},
    {"fc_paper_literal/inflection", "bandwidth 1/tau_peak (the paper's 100 Hz = 10 ms)", "Hz"},
    {"B_min/paper_procedure",
     "B = sigma_min/0.6643, the paper's procedure (non-overlapping, M = 2^k, L = T/M >= 2)", "deg/h"},
    {"tau_min/paper_procedure", "tau of that minimum", "s"},
    {"B_min_ratio/paper_procedure_9_clusters",
     "the same with L >= 9 clusters (paper's error formula <= 25 %), ratio", "ratio"},
    {"N_fit_ratio/fit", "N from `allanlab fit` (GLS, defaults), ratio", "ratio"},
    {"B_fit_ratio/fit", "B from `allanlab fit` (GLS, defaults), ratio", "ratio"},
};

// Coverage of the fit's profile-likelihood intervals (proportions, Wilson 95 %).
struct CoverageQuantity {
  const char* column;
  const char* label;
  double nominal;
};
constexpr CoverageQuantity kCoverages[] = {
    {"N_fit_in_ci68.3/fit", "N, 68.3 % interval", 0.683},
    {"N_fit_in_ci95/fit", "N, 95 % interval", 0.95},
    {"B_fit_in_ci68.3/fit", "B, 68.3 % interval", 0.683},
    {"B_fit_in_ci95/fit", "B, 95 % interval", 0.95},
};
// A coverage is "met" when its Wilson interval lies within the nominal level +- this.
constexpr double kCoverageBand = 0.025;

struct Row {
  std::string preset, quantity, unit;
  double truth = kNaN, paper = kNaN, mean = kNaN, std = kNaN, se = kNaN;
  double ratio_mean = kNaN, ratio_se = kNaN;
  std::int64_t count = 0, trials = 0;
  std::string note;
};

std::string Num(double v, int digits = 4) { return std::isfinite(v) ? SignificantDigits(v, digits) : "n/a"; }

std::vector<Row> BuildRows(const SweepSpec& spec, const std::vector<PointStats>& stats) {
  std::vector<Row> rows;
  for (const PointStats& ps : stats) {
    const SweepPoint& point = spec.points.at(static_cast<std::size_t>(ps.point));
    const SeedPaperTruth truth = TruthOf(point.model);
    const PaperNumbers* paper = PaperFor(point.model.name);
    for (const Quantity& q : kQuantities) {
      Row row;
      row.preset = point.model.name;
      row.quantity = q.label;
      row.unit = q.unit;
      row.trials = ps.trials;
      const std::string column = q.column;
      if (const ColumnStats* c = ps.Find(column); c && c->count > 0) {
        row.count = c->count;
        row.mean = c->mean;
        row.std = c->std;
        row.se = c->standard_error;
      }
      std::string ratio_column;
      if (column == "N_curve/paper") {
        row.truth = truth.n_deg_per_sqrt_h;
        ratio_column = "N_curve_ratio/paper";
        if (paper) {
          row.paper = paper->n_printed;
          row.note = "paper: sigma(1 s) = " + Num(paper->sigma_1s_deg_per_h) + " deg/h -> " +
                     Num(paper->sigma_1s_deg_per_h / 60.0) + ", printed " + Num(paper->n_printed);
        }
      } else if (column == "N_line/slope") {
        row.truth = truth.n_deg_per_sqrt_h;
        ratio_column = "N_line_ratio/slope";
      } else if (column == "sigma_min/curve") {
        row.truth = truth.b_floor_deg_per_h * kFloorFactor;
        if (paper) row.paper = paper->sigma_bias_deg_per_h;
        row.note = "truth = 0.6643 sqrt(B^2 + 2.617 N K)";
      } else if (column == "B_min/paper_procedure") {
        row.truth = truth.b_deg_per_h;
        ratio_column = "B_min_ratio/paper_procedure";
        row.note = "floor theory sqrt(B^2+2.617NK) = " + Num(truth.b_floor_deg_per_h);
      } else if (row.unit == "ratio") {
        row.truth = 1.0;
        ratio_column = column;
        if (column.find("_fit_") != std::string::npos) {
          const ColumnStats* failed = ps.Find("fit_failed/fit");
          row.note = "fit failed in " + Num(failed ? failed->mean * 100.0 : kNaN, 3) + " % of trials";
        }
      } else if (column == "B_min/paper") {
        row.truth = truth.b_deg_per_h;
        ratio_column = "B_min_ratio/paper";
        if (paper) {
          row.paper = paper->b_printed;
          row.note = "paper: " + Num(paper->sigma_bias_deg_per_h) + "/0.6643 = " +
                     Num(paper->sigma_bias_deg_per_h / kFloorFactor) + ", printed " +
                     Num(paper->b_printed) + "; floor theory sqrt(B^2+2.617NK) = " +
                     Num(truth.b_floor_deg_per_h);
        }
      } else if (column == "fc_first_order/inflection" || column == "fc_paper_rule/inflection" ||
                 column == "fc_paper_literal/inflection") {
        row.truth = truth.cutoff_hz;
        if (paper) row.paper = paper->bandwidth_hz;
        if (column == "fc_first_order/inflection") ratio_column = "fc_ratio/inflection";
        const ColumnStats* found = ps.Find("fc_found/inflection");
        row.note = "found in " + Num(found ? found->mean * 100.0 : kNaN, 3) + " % of trials";
      } else if (column == "peak_tau/inflection") {
        row.truth = truth.cutoff_hz > 0.0 ? 0.301 / truth.cutoff_hz : kNaN;
        row.note = "truth = 0.301/fc (first order), docs/theory.md §2.9";
      }
      if (!ratio_column.empty()) {
        if (const ColumnStats* c = ps.Find(ratio_column); c && c->count > 0) {
          row.ratio_mean = c->mean;
          row.ratio_se = c->standard_error;
        }
      } else if (row.truth > 0.0 && std::isfinite(row.mean)) {
        row.ratio_mean = row.mean / row.truth;
        row.ratio_se = row.se / row.truth;
      }
      rows.push_back(std::move(row));
    }
  }
  return rows;
}

std::string Csv(const std::vector<Row>& rows, const std::string& header) {
  std::ostringstream out;
  out << header
      << "preset,quantity,unit,truth,paper_printed,mc_mean,mc_std,mc_se,mean_ratio_to_truth,"
         "ratio_se,count,trials,note\n";
  for (const Row& r : rows) {
    out << r.preset << ",\"" << r.quantity << "\"," << r.unit << ',' << Num(r.truth, 6) << ','
        << Num(r.paper, 4) << ',' << Num(r.mean, 6) << ',' << Num(r.std, 4) << ','
        << Num(r.se, 3) << ',' << Num(r.ratio_mean, 5) << ',' << Num(r.ratio_se, 3) << ','
        << r.count << ',' << r.trials << ",\"" << r.note << "\"\n";
  }
  return out.str();
}

std::string Markdown(const SweepSpec& spec, const std::vector<Row>& rows,
                     const std::vector<PointStats>& stats, const std::string& question, const std::string& provenance) {
  std::ostringstream out;
  out << "# " << spec.name << ": the seed paper's procedure on simulated MG-25 and TG-100\n\n"
      << question << "\n\n## Provenance\n\n" << provenance << "\n"
      << "## The paper's printed numbers, recomputed\n\n"
         "| gyro | sigma(1 s) [deg/h] | N = sigma/60 [deg/sqrt(h)] | paper prints | "
         "sigma_bias [deg/h] | B = sigma/0.6643 [deg/h] | paper prints |\n"
         "|---|---|---|---|---|---|---|\n";
  for (const PaperNumbers& p : kPaper) {
    out << "| " << p.preset << " | " << Num(p.sigma_1s_deg_per_h) << " | "
        << Num(p.sigma_1s_deg_per_h / 60.0) << " | " << Num(p.n_printed) << " | "
        << Num(p.sigma_bias_deg_per_h) << " | " << Num(p.sigma_bias_deg_per_h / kFloorFactor)
        << " | " << Num(p.b_printed) << " |\n";
  }
  out << "\n## Monte Carlo: what the procedure returns vs the truth\n\n"
         "mean ± std over trials (the spread one record gives); ratio = mean reading / truth ± "
         "its standard error [95 % interval, ± 1.96 standard errors]. A bandwidth rule is tested "
         "only where the ADEV maximum lies above tau0 (found > 0).\n";
  std::string preset;
  for (const Row& r : rows) {
    if (r.preset != preset) {
      preset = r.preset;
      out << "\n### " << preset << "\n\n| quantity | unit | truth | paper | MC mean ± std | "
             "ratio to truth | found | note |\n|---|---|---|---|---|---|---|---|\n";
    }
    out << "| " << r.quantity << " | " << r.unit << " | " << Num(r.truth) << " | "
        << Num(r.paper) << " | " << Num(r.mean) << " ± " << Num(r.std, 2) << " | "
        << (std::isfinite(r.ratio_mean)
                ? Num(r.ratio_mean) + " ± " + Num(r.ratio_se, 2) + " [" +
                      Num(r.ratio_mean - 1.96 * r.ratio_se) + ", " +
                      Num(r.ratio_mean + 1.96 * r.ratio_se) + "]"
                : std::string("n/a"))
        << " | " << r.count << "/"
        << r.trials << " | " << r.note << " |\n";
  }
  out << "\n## Coverage of the fit's intervals\n\n"
         "`allanlab fit`'s profile-likelihood intervals of N and B: share of trials whose interval "
         "holds the truth, Wilson 95 % interval; met when that interval lies within the nominal "
         "level ± "
      << Num(kCoverageBand * 100.0, 2)
      << " points, not met when it lies outside, else undecided.\n\n"
         "| gyro | interval | coverage | Wilson 95 % | trials | verdict |\n|---|---|---|---|---|---|\n";
  for (const PointStats& ps : stats) {
    const std::string name = spec.points.at(static_cast<std::size_t>(ps.point)).model.name;
    for (const CoverageQuantity& q : kCoverages) {
      const ColumnStats* c = ps.Find(q.column);
      if (!c || c->count == 0) continue;
      const RateInterval w = WilsonInterval(c->mean, c->count);
      out << "| " << name << " | " << q.label << " | " << Num(c->mean, 3) << " | [" << Num(w.low, 3)
          << ", " << Num(w.high, 3) << "] | " << c->count << " | "
          << TargetVerdict(w, q.nominal - kCoverageBand, q.nominal + kCoverageBand) << " |\n";
    }
  }
  out << "\nFigures: " << spec.name << "_allan.png/.svg (exact OADEV and Monte Carlo band per "
      << "gyro), " << spec.name << "_coverage.png/.svg (coverage of the GR intervals per tau).\n";
  return out.str();
}

std::string AllanFigure(const SweepSpec& spec, const std::vector<PointStats>& stats) {
  std::ostringstream out;
  for (const PointStats& ps : stats) {
    const SweepPoint& point = spec.points.at(static_cast<std::size_t>(ps.point));
    const std::vector<std::int64_t> ms = SeedPaperAveragingFactors(spec, point);
    const std::vector<double> e = point.model.ExpectedAvar(
        ms, sim::RecordShape{point.num_samples, sim::AvarEstimatorKind::kOverlapping});
    out << "$p" << ps.point << " << EOD\n";
    for (std::size_t i = 0; i < ms.size(); ++i) {
      std::ostringstream name;
      name << "ratio/overlapping/m=" << ms[i];
      const ColumnStats* c = ps.Find(name.str());
      if (!c || c->count == 0) continue;
      const double tau = static_cast<double>(ms[i]) / point.model.sample_clock.rate_hz();
      out << SignificantDigits(tau, 8) << ' ' << SignificantDigits(std::sqrt(e[i]) * kRadPerSToDegPerH, 8)
          << ' ' << SignificantDigits(std::sqrt(e[i] * c->mean) * kRadPerSToDegPerH, 8) << ' '
          << SignificantDigits(std::sqrt(e[i] * c->mean * c->mean / (c->mean + c->std)) * kRadPerSToDegPerH, 8)
          << ' ' << SignificantDigits(std::sqrt(e[i] * (c->mean + c->std)) * kRadPerSToDegPerH, 8)
          << '\n';
    }
    out << "EOD\n";
  }
  out << "set multiplot layout 1," << stats.size() << " title '" << spec.name
      << ": OADEV, exact theory vs Monte Carlo mean, band x// (1 + std/mean)'\n"
      << "set logscale xy\nset format y '%g'\nset xlabel 'tau [s]'\nset ylabel 'ADEV [deg/h]'\n"
      << "set grid\nset key bottom left\n";
  for (const PointStats& ps : stats) {
    out << "set title '" << spec.points.at(static_cast<std::size_t>(ps.point)).model.name << "'\n"
        << "plot $p" << ps.point << " using 1:4:5 with filledcurves lc rgb '#b0c4de' title 'MC mean x// (1 + std/mean)', "
        << "$p" << ps.point << " using 1:2 with lines lw 2 lc rgb 'black' title 'exact theory', "
        << "$p" << ps.point << " using 1:3 with points pt 7 ps 0.5 lc rgb 'red' title 'MC mean'\n";
  }
  out << "unset multiplot\n";
  return out.str();
}

std::string CoverageFigure(const SweepSpec& spec, const std::vector<PointStats>& stats) {
  std::ostringstream out;
  out << "$c << EOD\n";
  for (const PointStats& ps : stats) {
    for (const ColumnStats& c : ps.columns) {
      if (c.column.rfind("in_ci", 0) != 0 || c.count == 0) continue;
      const double nominal = std::stod(c.column.substr(5)) / 100.0;
      out << SignificantDigits(nominal, 6) << ' ' << SignificantDigits(c.mean, 6) << ' '
          << SignificantDigits(CoverageStandardError(nominal, c.count), 4) << '\n';
    }
  }
  out << "EOD\nset title '" << spec.name
      << ": coverage of the GR chi-square intervals of OAVAR (each point one gyro and tau)'\n"
      << "set xlabel 'nominal coverage'\nset ylabel 'observed coverage'\nset grid\n"
      << "set xrange [0.5:1.0]\nset yrange [0.3:1.02]\nset key bottom right\n"
      << "plot x with lines lc rgb 'black' title 'observed = nominal', "
      << "$c using 1:2:3 with yerrorbars pt 7 ps 0.5 lc rgb 'blue' title 'Greenhall-Riley EDF'\n";
  return out.str();
}

}  // namespace

std::string SeedPaperExperiment::Question() const {
  return "Question: what does the seed paper's procedure (Mikheev et al. 2021: N = sigma(1 s)/60 "
         "read off the Allan diagram, B = minimum / 0.6643, bandwidth from the short-tau "
         "inflection) return on simulated records of its two gyros, how far is it from the "
         "truth the records were made from, and what does a correct estimate return beside it? "
         "Method: `trials` records per point (sim/presets mg25_mems and tg100 at 400 Hz; tg100 "
         "also at 4 kHz, where the short-tau ADEV maximum, ~0.3/fc = 3 ms, lies above tau0 and the "
         "bandwidth rule can be read). The paper's procedure as its equations 1-2 state it: "
         "non-overlapping clusters, L = T/M of them, M doubling while L >= 2 (the paper prints no "
         "tau range; its error formula 100/sqrt(2(L-1)) is also applied as L >= 9, 25 %), B from "
         "the lowest point. Beside it the dense overlapping ADEV to N/2 with the readings of "
         "estimators/fit/slope_method.h and bandwidth_estimate.h, and the correct estimate: "
         "`allanlab fit`'s defaults (GLS, term selection, profile-likelihood intervals) on the "
         "octave OAVAR curve at the taus the band-limit leaves unbiased. Reference: the models' "
         "coefficients; for the minimum also docs/theory.md §4.2's sqrt(B^2 + 2.617 N K). "
         "Read: the bias of each reading (ratio to truth with its 95 % interval) and the spread "
         "one record gives; the fit's interval coverage against its nominal level.";
}

bool SeedPaperExperiment::WriteReport(const SweepSpec& spec, const RunSummary& run,
                                      const std::vector<PointStats>& stats,
                                      const ReportContext& context, std::string* why) const {
  std::vector<Row> rows;
  std::string allan, coverage;
  try {
    rows = BuildRows(spec, stats);
    allan = AllanFigure(spec, stats);
    coverage = CoverageFigure(spec, stats);
  } catch (const std::exception& e) {
    if (why) *why = std::string("seed_paper report: ") + e.what();
    return false;
  }
  std::vector<std::pair<std::string, std::string>> extra = {
      {"estimator", "overlapping ADEV, Greenhall-Riley EDF"},
      {"taus", spec.taus + " plus tau = 1 s"},
      {"trials_failed", std::to_string(run.trials_failed)},
  };
  for (const SweepPoint& point : spec.points) {
    extra.emplace_back("point " + std::to_string(point.index),
                       point.model.name + ", " + std::to_string(point.num_samples) +
                           " samples at " + SignificantDigits(point.model.sample_clock.rate_hz(), 6) + " Hz");
  }
  const std::string base = context.output_dir + "/" + spec.name;
  const std::string csv = Csv(rows, ProvenanceBlock(spec, context, extra, "# "));
  const std::string md = Markdown(spec, rows, stats, Question(),
                                  "```\n" + ProvenanceBlock(spec, context, extra, "") + "```\n");
  return WriteFileAtomically(base + ".csv", csv, why) &&
         WriteFileAtomically(base + ".md", md, why) &&
         RenderGnuplotFigure(allan, base + "_allan", 1300, 600, why) &&
         RenderGnuplotFigure(coverage, base + "_coverage", 900, 650, why);
}

}  // namespace allanlab::experiments
