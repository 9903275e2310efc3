#include "experiments/default_intervals.h"

#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "estimators/avar.h"
#include "experiments/interval_coverage.h"
#include "experiments/plain_noise.h"
#include "experiments/report_files.h"

namespace allanlab::experiments {
namespace {

using estimators::ConfidenceMethod;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// The claim: every cell within 2 points of its nominal level.
constexpr double kBand = 0.02;

struct Method {
  const char* id;
  ConfidenceMethod method;
};
constexpr Method kMethods[] = {{"auto", ConfidenceMethod::kAuto},
                               {"gr", ConfidenceMethod::kGreenhallRiley}};

std::string Key(std::string_view quantity, std::string_view method, const std::string& noise,
                std::int64_t m) {
  std::ostringstream out;
  out << quantity << '/';
  if (!method.empty()) out << method << '/';
  out << noise << "/m=" << m;
  return out.str();
}

std::string LevelKey(double level) { return "in_ci" + SignificantDigits(100.0 * level, 3); }

}  // namespace

std::vector<std::int64_t> DefaultIntervalFactors(std::int64_t num_samples) {
  std::vector<std::int64_t> ms;
  for (std::int64_t m = 1; num_samples / m >= 8; m *= 2) ms.push_back(m);
  if (ms.empty()) throw std::invalid_argument("records need at least 8 samples");
  return ms;
}

std::vector<std::string> DefaultIntervalsDriver::Columns(const SweepSpec& spec,
                                                         const SweepPoint& point) const {
  std::vector<std::string> columns;
  for (PlainNoise noise : PlainNoises()) {
    const std::string id = PlainNoiseId(noise);
    for (std::int64_t m : DefaultIntervalFactors(point.num_samples)) {
      columns.push_back(Key("ratio", "", id, m));
      for (const Method& method : kMethods) {
        columns.push_back(Key("edf", method.id, id, m));
        for (double level : spec.confidence_levels) {
          columns.push_back(Key(LevelKey(level), method.id, id, m));
        }
      }
    }
  }
  return columns;
}

std::unique_ptr<TrialWorkspace> DefaultIntervalsDriver::MakeWorkspace() const {
  return std::make_unique<TrialWorkspace>();
}

std::vector<double> DefaultIntervalsDriver::Run(const SweepSpec& spec, const SweepPoint& point,
                                                std::int64_t trial, TrialWorkspace*) const {
  const std::vector<std::int64_t> ms = DefaultIntervalFactors(point.num_samples);
  std::vector<double> row;
  for (PlainNoise noise : PlainNoises()) {
    const std::vector<double> record = GeneratePlain(
        noise, point.num_samples, PointSeed(spec.seed, point.index), static_cast<std::uint64_t>(trial));
    std::vector<estimators::AvarSummary> summaries;
    for (const Method& method : kMethods) {
      estimators::AvarOptions options;  // `allanlab avar`'s defaults: octave OAVAR
      options.sample_clock = point.model.sample_clock;
      options.confidence_method = method.method;
      estimators::AvarSummary summary;
      if (!estimators::ComputeAvar(options, record, &summary)) {
        throw std::runtime_error(PlainNoiseLabel(noise) + ": " + summary.message);
      }
      summaries.push_back(std::move(summary));
    }
    for (std::int64_t m : ms) {
      const double expected = PlainExpectedAvar(noise, m);
      bool ratio_written = false;
      for (std::size_t k = 0; k < summaries.size(); ++k) {
        const estimators::AvarPoint* p = nullptr;
        for (const auto& candidate : summaries[k].points) {
          if (candidate.m == m) p = &candidate;
        }
        if (!ratio_written) {
          row.push_back(p ? p->value / expected : kNaN);
          ratio_written = true;
        }
        row.push_back(p && p->edf > 0.0 ? p->edf : kNaN);
        AppendCoverageHits(summaries[k], p, expected, spec.confidence_levels, &row);
      }
    }
  }
  return row;
}

std::string DefaultIntervalsExperiment::Question() const {
  return "Do `allanlab avar`'s default intervals (octave OAVAR, --ci auto: the EDF measured on "
         "the record's own Allan differences at short taus, Greenhall-Riley at the identified "
         "noise type elsewhere) cover the true Allan variance at their nominal 68.3 % and 95 % "
         "within 2 points, at every octave tau with at least 8 clusters, for white, flicker and "
         "random-walk rate noise? Records: experiments/plain_noise.h, written apart from sim/ "
         "(standard-library random numbers; flicker as a sum of 47 AR(1) processes; the random "
         "walk point-sampled, as a cumulative sum, and averaged over each sample interval), each "
         "with its exact expected Allan variance. Beside it, the Greenhall-Riley intervals at the "
         "noise type identified at each tau alone (--ci gr, Stable32's method, the default "
         "before). Criterion: met when the Wilson 95 % interval of the observed coverage lies "
         "inside nominal +- 2 points; not met when it lies wholly outside; else undecided.";
}

namespace {

struct Cell {
  std::string noise, label;
  std::int64_t m = 0, clusters = 0, trials = 0;
  double tau_s = 0.0, bias = kNaN, bias_se = kNaN, empirical_edf = kNaN;
  double edf[2] = {kNaN, kNaN};
  double coverage[2][2] = {{kNaN, kNaN}, {kNaN, kNaN}};  // [method][level]
  std::int64_t coverage_n[2][2] = {{0, 0}, {0, 0}};
  RateInterval wilson[2][2];
  std::string verdict[2];
};

std::vector<Cell> BuildCells(const SweepSpec& spec, const SweepPoint& point, const PointStats& ps) {
  std::vector<Cell> cells;
  for (PlainNoise noise : PlainNoises()) {
    const std::string id = PlainNoiseId(noise);
    for (std::int64_t m : DefaultIntervalFactors(point.num_samples)) {
      Cell c;
      c.noise = id;
      c.label = PlainNoiseLabel(noise);
      c.m = m;
      c.tau_s = static_cast<double>(m) / point.model.sample_clock.rate_hz();
      c.clusters = point.num_samples / m;
      if (const ColumnStats* r = ps.Find(Key("ratio", "", id, m)); r && r->count > 1) {
        c.trials = r->count;
        c.bias = r->mean - 1.0;
        c.bias_se = r->standard_error;
        c.empirical_edf = 2.0 * r->mean * r->mean / (r->std * r->std);
      }
      for (int k = 0; k < 2; ++k) {
        if (const ColumnStats* e = ps.Find(Key("edf", kMethods[k].id, id, m))) c.edf[k] = e->mean;
        std::string verdict = "met";
        for (std::size_t l = 0; l < spec.confidence_levels.size() && l < 2; ++l) {
          const double level = spec.confidence_levels[l];
          const ColumnStats* cov = ps.Find(Key(LevelKey(level), kMethods[k].id, id, m));
          if (!cov || cov->count == 0) {
            verdict = "undecided";
            continue;
          }
          c.coverage[k][l] = cov->mean;
          c.coverage_n[k][l] = cov->count;
          c.wilson[k][l] = WilsonInterval(cov->mean, cov->count);
          const std::string v = TargetVerdict(c.wilson[k][l], level - kBand, level + kBand);
          if (v == "not met" || (v == "undecided" && verdict == "met")) verdict = v;
        }
        c.verdict[k] = verdict;
      }
      cells.push_back(c);
    }
  }
  return cells;
}

std::string Interval3(double rate, const RateInterval& w) {
  if (!std::isfinite(rate)) return "n/a";
  return SignificantDigits(rate, 3) + " [" + SignificantDigits(w.low, 3) + ", " + SignificantDigits(w.high, 3) + "]";
}

std::string CoverageFigure(const SweepSpec& spec, const std::vector<Cell>& cells) {
  std::ostringstream out;
  out << "set multiplot layout 1,2 title 'avar default intervals (--ci auto, filled) and "
         "Greenhall-Riley at the per-tau noise type (--ci gr, open): coverage per tau, Wilson 95 %'\n";
  for (std::size_t l = 0; l < spec.confidence_levels.size() && l < 2; ++l) {
    const double level = spec.confidence_levels[l];
    out << "set logscale x 2\nset xlabel 'averaging factor m (tau = m tau0)'\n"
        << "set ylabel 'coverage'\nset key bottom left\nset grid\n"
        << "set title 'nominal " << SignificantDigits(100.0 * level, 3) << " %'\n"
        << "set yrange [" << level - 0.12 << ":" << std::min(1.0, level + 0.1) << "]\n";
    int block = 0;
    std::ostringstream plot;
    plot << "plot " << level - kBand << " dt 2 lc rgb 'gray' title 'nominal +- 2 points', "
         << level + kBand << " dt 2 lc rgb 'gray' notitle";
    int colour = 0;
    for (PlainNoise noise : PlainNoises()) {
      const std::string id = PlainNoiseId(noise);
      for (int k = 0; k < 2; ++k) {
        out << "$d" << l << "_" << block << " << EOD\n";
        for (const Cell& c : cells) {
          if (c.noise != id || !std::isfinite(c.coverage[k][l])) continue;
          // Methods side by side: a small offset in m keeps the bars apart.
          const double x = static_cast<double>(c.m) * (k == 0 ? 1.0 : 1.08) *
                           std::pow(1.04, colour);
          out << x << ' ' << c.coverage[k][l] << ' ' << c.wilson[k][l].low << ' '
              << c.wilson[k][l].high << '\n';
        }
        out << "EOD\n";
        plot << ", $d" << l << "_" << block << " using 1:2:3:4 with yerrorlines lc " << colour + 1
             << " pt " << (k == 0 ? 7 : 6) << " dt " << (k == 0 ? 1 : 3) << " title '"
             << PlainNoiseLabel(noise) << (k == 0 ? " auto" : " gr") << "'";
        ++block;
      }
      ++colour;
    }
    out << plot.str() << "\n";
  }
  out << "unset multiplot\n";
  return out.str();
}

}  // namespace

bool DefaultIntervalsExperiment::WriteReport(const SweepSpec& spec, const RunSummary& run,
                                             const std::vector<PointStats>& stats,
                                             const ReportContext& context, std::string* why) const {
  (void)run;
  std::vector<std::pair<std::string, std::string>> extra = {
      {"records", "experiments/plain_noise.h (not sim/), unit scale"},
      {"intervals", "allanlab avar defaults: octave OAVAR, --ci auto; and --ci gr"}};
  std::ostringstream csv, md;
  const std::string base = context.output_dir + "/" + spec.name;
  csv << ProvenanceBlock(spec, context, extra, "# ");
  csv << "point,noise,m,tau_s,clusters,trials,bias,bias_se,empirical_edf";
  for (const Method& method : kMethods) {
    csv << ",edf_" << method.id;
    for (double level : spec.confidence_levels) {
      const std::string l = SignificantDigits(100.0 * level, 3);
      csv << ",coverage" << l << '_' << method.id << ",wilson_low" << l << '_' << method.id
          << ",wilson_high" << l << '_' << method.id;
    }
    csv << ",verdict_" << method.id;
  }
  csv << '\n';
  md << "# " << spec.name << ": coverage of `allanlab avar`'s default intervals\n\n"
     << Question() << "\n\n## Provenance\n\n```\n"
     << ProvenanceBlock(spec, context, extra, "") << "```\n\n";
  std::vector<Cell> all;
  for (const PointStats& ps : stats) {
    const SweepPoint& point = spec.points.at(static_cast<std::size_t>(ps.point));
    const std::vector<Cell> cells = BuildCells(spec, point, ps);
    int met[2] = {0, 0}, not_met[2] = {0, 0};
    for (const Cell& c : cells) {
      for (int k = 0; k < 2; ++k) {
        met[k] += c.verdict[k] == "met";
        not_met[k] += c.verdict[k] == "not met";
      }
    }
    md << "## " << point.num_samples << " samples at " << SignificantDigits(point.model.sample_clock.rate_hz(), 4)
       << " Hz, " << (cells.empty() ? 0 : cells.front().trials) << " trials per cell\n\n"
       << "Cells (noise x tau) within nominal +- 2 points at both levels: --ci auto " << met[0]
       << " met, " << not_met[0] << " not met, " << cells.size() - met[0] - not_met[0]
       << " undecided of " << cells.size() << "; --ci gr " << met[1] << " met, " << not_met[1]
       << " not met, " << cells.size() - met[1] - not_met[1] << " undecided.\n\n"
       << "| noise | m | clusters | bias ± se | EDF auto / gr / observed | 68.3 % auto [Wilson] | "
          "95 % auto [Wilson] | auto | 68.3 % gr [Wilson] | 95 % gr [Wilson] | gr |\n"
       << "|---|---|---|---|---|---|---|---|---|---|---|\n";
    for (const Cell& c : cells) {
      md << "| " << c.label << " | " << c.m << " | " << c.clusters << " | "
         << SignificantDigits(c.bias, 2) << " ± " << SignificantDigits(c.bias_se, 2) << " | "
         << SignificantDigits(c.edf[0], 4) << " / " << SignificantDigits(c.edf[1], 4) << " / "
         << SignificantDigits(c.empirical_edf, 4) << " | " << Interval3(c.coverage[0][0], c.wilson[0][0])
         << " | " << Interval3(c.coverage[0][1], c.wilson[0][1]) << " | " << c.verdict[0] << " | "
         << Interval3(c.coverage[1][0], c.wilson[1][0]) << " | "
         << Interval3(c.coverage[1][1], c.wilson[1][1]) << " | " << c.verdict[1] << " |\n";
      csv << ps.point << ',' << c.noise << ',' << c.m << ',' << SignificantDigits(c.tau_s, 9) << ','
          << c.clusters << ',' << c.trials << ',' << SignificantDigits(c.bias, 6) << ','
          << SignificantDigits(c.bias_se, 4) << ',' << SignificantDigits(c.empirical_edf, 6);
      for (int k = 0; k < 2; ++k) {
        csv << ',' << SignificantDigits(c.edf[k], 6);
        for (std::size_t l = 0; l < spec.confidence_levels.size() && l < 2; ++l) {
          csv << ',' << SignificantDigits(c.coverage[k][l], 6) << ',' << SignificantDigits(c.wilson[k][l].low, 6)
              << ',' << SignificantDigits(c.wilson[k][l].high, 6);
        }
        csv << ',' << c.verdict[k];
      }
      csv << '\n';
    }
    md << "\nEDF observed = 2 mean^2 / variance of the estimate over the trials. Bias = mean of "
          "OAVAR_hat / E[OAVAR_hat] - 1.\n\n";
    all.insert(all.end(), cells.begin(), cells.end());
  }
  md << "![coverage](" << spec.name << "_coverage.png)\n";
  return WriteFileAtomically(base + ".csv", csv.str(), why) &&
         WriteFileAtomically(base + ".md", md.str(), why) &&
         RenderGnuplotFigure(CoverageFigure(spec, all), base + "_coverage", 1500, 650, why);
}

}  // namespace allanlab::experiments
