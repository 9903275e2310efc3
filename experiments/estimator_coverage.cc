#include "experiments/estimator_coverage.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>

#include "estimators/avar.h"
#include "experiments/family_expectation.h"
#include "experiments/interval_coverage.h"
#include "experiments/plain_noise.h"
#include "experiments/report_files.h"

namespace allanlab::experiments {
namespace {

using estimators::Statistic;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// The claim: every cell within 2 points of its nominal level.
constexpr double kBand = 0.02;

std::string Key(std::string_view quantity, const std::string& noise, Statistic s, std::int64_t m) {
  std::ostringstream out;
  out << quantity << '/' << noise << '/' << estimators::StatisticId(s) << "/m=" << m;
  return out.str();
}

std::string LevelKey(double level) { return "in_ci" + SignificantDigits(100.0 * level, 3); }

// The plain noise behind a single-noise id.
bool PlainOf(const std::string& noise, PlainNoise* out) {
  if (noise == "white") *out = PlainNoise::kWhite;
  else if (noise == "flicker") *out = PlainNoise::kFlicker;
  else if (noise == "rw") *out = PlainNoise::kRandomWalk;
  else if (noise == "quantization") *out = PlainNoise::kQuantization;
  else return false;
  return true;
}

// Expectations of a point, computed once per workspace (TOTVAR's edge filters cost ~m^3).
class Workspace : public TrialWorkspace {
 public:
  int point = -1;
  std::map<std::string, double> expected;  // by ratio key
};

}  // namespace

const std::vector<std::string>& EstimatorCoverageNoises() {
  static const std::vector<std::string> kAll = {"white", "flicker", "rw", "quantization", "composite"};
  return kAll;
}

const std::vector<Statistic>& EstimatorCoverageStatistics() {
  static const std::vector<Statistic> kAll = {
      Statistic::kAllanNonOverlapping, Statistic::kAllanOverlapping, Statistic::kModifiedAllan,
      Statistic::kHadamardNonOverlapping, Statistic::kHadamardOverlapping, Statistic::kTotal,
      Statistic::kTime};
  return kAll;
}

std::vector<double> EstimatorCoverageRecord(const std::string& noise, std::int64_t n,
                                            std::uint64_t seed, std::uint64_t stream) {
  PlainNoise plain;
  if (PlainOf(noise, &plain)) return GeneratePlain(plain, n, seed, stream);
  if (noise != "composite") throw std::invalid_argument("estimator coverage: unknown noise " + noise);
  // Each component from its own engine (GeneratePlain seeds with the noise kind too).
  std::vector<double> y = GeneratePlain(PlainNoise::kWhite, n, seed, stream);
  const std::vector<double> flicker = GeneratePlain(PlainNoise::kFlicker, n, seed, stream);
  const std::vector<double> walk = GeneratePlain(PlainNoise::kRandomWalk, n, seed, stream);
  for (std::size_t i = 0; i < y.size(); ++i) {
    y[i] += kCompositeFlicker * flicker[i] + kCompositeRandomWalk * walk[i];
  }
  return y;
}

double EstimatorCoverageExpectation(const std::string& noise, Statistic statistic, std::int64_t m,
                                    std::int64_t n, double tau0_s) {
  PlainNoise plain;
  Autocovariance r;
  if (PlainOf(noise, &plain)) {
    r = [plain](std::int64_t k) { return PlainAutocovariance(plain, k); };
  } else if (noise == "composite") {
    r = [](std::int64_t k) {
      return PlainAutocovariance(PlainNoise::kWhite, k) +
             kCompositeFlicker * kCompositeFlicker * PlainAutocovariance(PlainNoise::kFlicker, k) +
             kCompositeRandomWalk * kCompositeRandomWalk * PlainAutocovariance(PlainNoise::kRandomWalk, k);
    };
  } else {
    throw std::invalid_argument("estimator coverage: unknown noise " + noise);
  }
  return FamilyExpectation(statistic, m, n, tau0_s, r);
}

std::vector<std::int64_t> EstimatorCoverageFactors(Statistic statistic, std::int64_t n) {
  std::vector<std::int64_t> ms;
  for (std::int64_t m = 1; n / m >= 8 && m <= estimators::MaxAveragingFactor(statistic, n); m *= 2) {
    ms.push_back(m);
  }
  if (ms.empty()) throw std::invalid_argument("records need at least 8 samples");
  return ms;
}

std::vector<std::string> EstimatorCoverageDriver::Columns(const SweepSpec& spec,
                                                          const SweepPoint& point) const {
  std::vector<std::string> columns;
  for (const std::string& noise : EstimatorCoverageNoises()) {
    for (Statistic s : EstimatorCoverageStatistics()) {
      for (std::int64_t m : EstimatorCoverageFactors(s, point.num_samples)) {
        columns.push_back(Key("ratio", noise, s, m));
        for (double level : spec.confidence_levels) columns.push_back(Key(LevelKey(level), noise, s, m));
      }
    }
  }
  return columns;
}

std::unique_ptr<TrialWorkspace> EstimatorCoverageDriver::MakeWorkspace() const {
  return std::make_unique<Workspace>();
}

std::vector<double> EstimatorCoverageDriver::Run(const SweepSpec& spec, const SweepPoint& point,
                                                 std::int64_t trial, TrialWorkspace* workspace) const {
  auto* ws = dynamic_cast<Workspace*>(workspace);
  Workspace local;
  if (!ws) ws = &local;
  const double tau0 = point.model.sample_clock.period_s();
  const std::int64_t n = point.num_samples;
  if (ws->point != point.index) {
    ws->expected.clear();
    for (const std::string& noise : EstimatorCoverageNoises()) {
      for (Statistic s : EstimatorCoverageStatistics()) {
        for (std::int64_t m : EstimatorCoverageFactors(s, n)) {
          ws->expected[Key("ratio", noise, s, m)] = EstimatorCoverageExpectation(noise, s, m, n, tau0);
        }
      }
    }
    ws->point = point.index;
  }
  std::vector<double> row;
  for (const std::string& noise : EstimatorCoverageNoises()) {
    const std::vector<double> record = EstimatorCoverageRecord(
        noise, n, PointSeed(spec.seed, point.index), static_cast<std::uint64_t>(trial));
    for (Statistic s : EstimatorCoverageStatistics()) {
      const std::vector<std::int64_t> ms = EstimatorCoverageFactors(s, n);
      estimators::AvarOptions options;  // `allanlab avar --estimator <s>`'s defaults
      options.statistic = s;
      options.sample_clock = point.model.sample_clock;
      options.taus.kind = estimators::TauGridKind::kExplicit;
      for (std::int64_t m : ms) options.taus.explicit_taus_s.push_back(static_cast<double>(m) * tau0);
      options.confidence_method = estimators::ConfidenceMethod::kAuto;
      estimators::AvarSummary summary;
      if (!estimators::ComputeAvar(options, record, &summary)) {
        throw std::runtime_error(noise + " " + std::string(estimators::StatisticId(s)) + ": " + summary.message);
      }
      for (std::int64_t m : ms) {
        const double expected = ws->expected.at(Key("ratio", noise, s, m));
        const estimators::AvarPoint* p = nullptr;
        for (const auto& candidate : summary.points) {
          if (candidate.m == m) p = &candidate;
        }
        row.push_back(p ? p->value / expected : kNaN);
        AppendCoverageHits(summary, p, expected, spec.confidence_levels, &row);
      }
    }
  }
  return row;
}

std::string EstimatorCoverageExperiment::Question() const {
  return "What bias and what interval coverage does each Allan-family estimator (AVAR, OAVAR, "
         "MVAR, HVAR, OHVAR, TOTVAR, TDEV) have with `allanlab avar`'s default intervals (--ci "
         "auto), under white, flicker, random-walk, quantization and composite noise, at every "
         "octave tau with at least 8 clusters? Records: experiments/plain_noise.h, written apart "
         "from sim/ (standard-library random numbers; flicker as 47 AR(1) processes; quantization "
         "as differenced white angle noise; the composite a sum of white, flicker and random "
         "walk). Expectations: experiments/family_expectation.h, each statistic's own filter "
         "applied to the records' autocovariance (docs/theory.md §1.2, §2.10; TOTVAR with its "
         "reflected ends, NIST SP 1065), apart from the estimators; they reproduce the closed "
         "forms of docs/theory.md §2.1-2.3. Bias = mean(estimate / expectation) - 1 (TDEV: of "
         "TDEV^2). Coverage: the share of records whose chi-square interval at the default EDF "
         "holds the expectation, Wilson 95 % interval; met when it lies inside nominal +- 2 "
         "points, not met when wholly outside, else undecided. Per statistic and noise the median "
         "cell over tau is shown beside the worst one.";
}

namespace {

struct CellStats {
  std::string noise;
  Statistic statistic;
  std::int64_t m = 0, trials = 0;
  double bias = kNaN, bias_se = kNaN;
  std::vector<double> coverage;
  std::vector<std::int64_t> coverage_n;
  std::vector<RateInterval> wilson;
  std::vector<std::string> verdict;
};

std::string Interval3(double rate, const RateInterval& w) {
  if (!std::isfinite(rate)) return "n/a";
  return SignificantDigits(rate, 3) + " [" + SignificantDigits(w.low, 3) + ", " + SignificantDigits(w.high, 3) + "]";
}

std::string StatisticLabel(Statistic s) {
  switch (s) {
    case Statistic::kAllanNonOverlapping: return "AVAR";
    case Statistic::kAllanOverlapping: return "OAVAR";
    case Statistic::kModifiedAllan: return "MVAR";
    case Statistic::kHadamardNonOverlapping: return "HVAR";
    case Statistic::kHadamardOverlapping: return "OHVAR";
    case Statistic::kTotal: return "TOTVAR";
    case Statistic::kTime: return "TDEV^2";
  }
  return "?";
}

}  // namespace

bool EstimatorCoverageExperiment::WriteReport(const SweepSpec& spec, const RunSummary& run,
                                              const std::vector<PointStats>& stats,
                                              const ReportContext& context, std::string* why) const {
  const std::size_t levels = spec.confidence_levels.size();
  std::vector<std::pair<std::string, std::string>> extra = {
      {"records", "experiments/plain_noise.h (not sim/), unit scale; composite = white + " +
                      SignificantDigits(kCompositeFlicker, 3) + " flicker + " +
                      SignificantDigits(kCompositeRandomWalk, 3) + " random walk"},
      {"expectations", "experiments/family_expectation.h (each statistic's filter on the autocovariance)"},
      {"intervals", "allanlab avar defaults (--ci auto), chi-square at the default EDF"},
      {"trials_failed", std::to_string(run.trials_failed)}};
  std::ostringstream csv, md;
  csv << ProvenanceBlock(spec, context, extra, "# ");
  csv << "point,noise,statistic,m,trials,bias,bias_se";
  for (double level : spec.confidence_levels) {
    const std::string l = SignificantDigits(100.0 * level, 3);
    csv << ",coverage" << l << ",wilson_low" << l << ",wilson_high" << l << ",verdict" << l;
  }
  csv << '\n';
  md << "# " << spec.name << ": bias and default-interval coverage of every Allan-family estimator\n\n"
     << Question() << "\n\n## Provenance\n\n```\n" << ProvenanceBlock(spec, context, extra, "")
     << "```\n";
  for (const PointStats& ps : stats) {
    const SweepPoint& point = spec.points.at(static_cast<std::size_t>(ps.point));
    std::vector<CellStats> cells;
    for (const std::string& noise : EstimatorCoverageNoises()) {
      for (Statistic s : EstimatorCoverageStatistics()) {
        for (std::int64_t m : EstimatorCoverageFactors(s, point.num_samples)) {
          CellStats c;
          c.noise = noise;
          c.statistic = s;
          c.m = m;
          if (const ColumnStats* r = ps.Find(Key("ratio", noise, s, m)); r && r->count > 1) {
            c.trials = r->count;
            c.bias = r->mean - 1.0;
            c.bias_se = r->standard_error;
          }
          for (double level : spec.confidence_levels) {
            const ColumnStats* cov = ps.Find(Key(LevelKey(level), noise, s, m));
            const bool has = cov && cov->count > 0;
            c.coverage.push_back(has ? cov->mean : kNaN);
            c.coverage_n.push_back(has ? cov->count : 0);
            c.wilson.push_back(has ? WilsonInterval(cov->mean, cov->count) : RateInterval{kNaN, kNaN});
            c.verdict.push_back(has ? TargetVerdict(c.wilson.back(), level - kBand, level + kBand) : "undecided");
          }
          cells.push_back(std::move(c));
        }
      }
    }
    for (const CellStats& c : cells) {
      csv << ps.point << ',' << c.noise << ',' << estimators::StatisticId(c.statistic) << ',' << c.m
          << ',' << c.trials << ',' << SignificantDigits(c.bias, 6) << ',' << SignificantDigits(c.bias_se, 4);
      for (std::size_t l = 0; l < levels; ++l) {
        csv << ',' << SignificantDigits(c.coverage[l], 6) << ',' << SignificantDigits(c.wilson[l].low, 6) << ','
            << SignificantDigits(c.wilson[l].high, 6) << ',' << c.verdict[l];
      }
      csv << '\n';
    }
    // Summary per (statistic, noise): the median cell over tau and the worst one.
    std::int64_t trials = 0;
    int met = 0, not_met = 0, total = 0;
    for (const CellStats& c : cells) {
      trials = std::max(trials, c.trials);
      for (const std::string& v : c.verdict) {
        ++total;
        met += v == "met";
        not_met += v == "not met";
      }
    }
    double worst_se = 0.0;
    for (double level : spec.confidence_levels) {
      worst_se = std::max(worst_se, std::sqrt(level * (1.0 - level) / std::max<double>(1.0, static_cast<double>(trials))));
    }
    md << "\n## " << point.num_samples << " samples, " << trials << " trials per cell\n\n"
       << "Coverage standard error at the nominal levels: <= " << SignificantDigits(100.0 * worst_se, 2)
       << " points. Cells (statistic x noise x tau x level) within nominal +- 2 points: " << met
       << " met, " << not_met << " not met, " << total - met - not_met << " undecided of " << total
       << ".\n\nbias: median over tau, and the largest |bias| in standard errors with its m. "
          "Coverage: median over tau; worst = farthest from nominal, with its Wilson 95 % interval "
          "and m; verdicts counted over the taus.\n\n| estimator | noise | bias median | bias worst (m) |";
    for (double level : spec.confidence_levels) {
      const std::string l = SignificantDigits(100.0 * level, 3);
      md << " " << l << " % median | " << l << " % worst [Wilson] (m) | " << l << " % met / not / undecided |";
    }
    md << "\n|---|---|---|---|";
    for (std::size_t l = 0; l < levels; ++l) md << "---|---|---|";
    md << "\n";
    for (Statistic s : EstimatorCoverageStatistics()) {
      for (const std::string& noise : EstimatorCoverageNoises()) {
        std::vector<const CellStats*> group;
        for (const CellStats& c : cells) {
          if (c.statistic == s && c.noise == noise) group.push_back(&c);
        }
        if (group.empty()) continue;
        auto median = [](std::vector<double> v) {
          v.erase(std::remove_if(v.begin(), v.end(), [](double x) { return !std::isfinite(x); }), v.end());
          if (v.empty()) return kNaN;
          std::sort(v.begin(), v.end());
          const std::size_t h = v.size() / 2;
          return v.size() % 2 ? v[h] : 0.5 * (v[h - 1] + v[h]);
        };
        std::vector<double> biases;
        const CellStats* worst_bias = nullptr;
        for (const CellStats* c : group) {
          biases.push_back(c->bias);
          if (std::isfinite(c->bias) && c->bias_se > 0.0 &&
              (!worst_bias || std::abs(c->bias) / c->bias_se > std::abs(worst_bias->bias) / worst_bias->bias_se)) {
            worst_bias = c;
          }
        }
        md << "| " << StatisticLabel(s) << " | " << noise << " | " << SignificantDigits(median(biases), 2) << " | "
           << (worst_bias ? SignificantDigits(worst_bias->bias, 2) + " ± " + SignificantDigits(worst_bias->bias_se, 2) +
                                " (" + std::to_string(worst_bias->m) + ")"
                          : "n/a")
           << " |";
        for (std::size_t l = 0; l < levels; ++l) {
          const double level = spec.confidence_levels[l];
          std::vector<double> coverages;
          const CellStats* worst = nullptr;
          int lmet = 0, lnot = 0;
          for (const CellStats* c : group) {
            coverages.push_back(c->coverage[l]);
            if (std::isfinite(c->coverage[l]) &&
                (!worst || std::abs(c->coverage[l] - level) > std::abs(worst->coverage[l] - level))) {
              worst = c;
            }
            lmet += c->verdict[l] == "met";
            lnot += c->verdict[l] == "not met";
          }
          md << " " << SignificantDigits(median(coverages), 3) << " | "
             << (worst ? Interval3(worst->coverage[l], worst->wilson[l]) + " (" + std::to_string(worst->m) + ")"
                       : "n/a")
             << " | " << lmet << " / " << lnot << " / " << static_cast<int>(group.size()) - lmet - lnot << " |";
        }
        md << "\n";
      }
    }
  }
  md << "\nEvery cell (statistic, noise, m) with its bias, coverage, Wilson interval and verdict is in "
     << spec.name << ".csv.\n";
  const std::string base = context.output_dir + "/" + spec.name;
  return WriteFileAtomically(base + ".csv", csv.str(), why) &&
         WriteFileAtomically(base + ".md", md.str(), why);
}

}  // namespace allanlab::experiments
