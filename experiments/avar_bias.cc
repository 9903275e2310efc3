#include "experiments/avar_bias.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <stdexcept>

#include "estimators/allan_family.h"
#include "estimators/tau_grid.h"
#include "experiments/report_files.h"
#include "common/number_text.h"

namespace allanlab::experiments {
namespace {

bool HasExactExpectation(estimators::Statistic s) {
  return s == estimators::Statistic::kAllanOverlapping ||
         s == estimators::Statistic::kAllanNonOverlapping;
}

sim::AvarEstimatorKind KindOf(estimators::Statistic s) {
  return s == estimators::Statistic::kAllanNonOverlapping ? sim::AvarEstimatorKind::kNonOverlapping
                                                          : sim::AvarEstimatorKind::kOverlapping;
}

std::vector<estimators::Statistic> Statistics(const SweepSpec& spec) {
  std::vector<estimators::Statistic> out;
  for (estimators::Statistic s : spec.estimators) {
    if (HasExactExpectation(s)) out.push_back(s);
  }
  return out;
}

std::vector<std::int64_t> AveragingFactors(const SweepSpec& spec, const SweepPoint& point) {
  estimators::TauGridOptions grid;
  std::string why;
  if (!estimators::TauGridOptions::Parse(spec.taus, &grid, &why)) throw std::invalid_argument(why);
  std::vector<std::int64_t> ms;
  for (std::int64_t m :
       estimators::CandidateAveragingFactors(grid, point.model.sample_clock.period_s(), point.num_samples / 4)) {
    if (m >= 1) ms.push_back(m);
  }
  return ms;
}

struct Workspace : TrialWorkspace {
  int point = -1;
  std::vector<std::int64_t> ms;
  std::vector<std::vector<double>> expected;  // per statistic, per m
  estimators::AllanFamilyWorkspace allan;
};

}  // namespace

std::vector<std::string> AvarBiasDriver::Columns(const SweepSpec& spec, const SweepPoint& point) const {
  std::vector<std::string> columns;
  const std::vector<std::int64_t> ms = AveragingFactors(spec, point);
  for (estimators::Statistic s : Statistics(spec)) {
    for (std::int64_t m : ms) {
      std::string name = "avar_ratio/";
      name += estimators::StatisticId(s);
      name += "/m=" + std::to_string(m);
      columns.push_back(std::move(name));
    }
  }
  return columns;
}

std::unique_ptr<TrialWorkspace> AvarBiasDriver::MakeWorkspace() const {
  return std::make_unique<Workspace>();
}

std::vector<double> AvarBiasDriver::Run(const SweepSpec& spec, const SweepPoint& point,
                                        std::int64_t trial, TrialWorkspace* workspace) const {
  auto* w = static_cast<Workspace*>(workspace);
  const std::vector<estimators::Statistic> statistics = Statistics(spec);
  if (w->point != point.index) {
    w->ms = AveragingFactors(spec, point);
    w->expected.clear();
    for (estimators::Statistic s : statistics) {
      w->expected.push_back(point.model.ExpectedAvar(w->ms, sim::RecordShape{point.num_samples, KindOf(s)}));
    }
    w->point = point.index;
  }
  const std::vector<double> rate = point.model.Generate(
      PointSeed(spec.seed, point.index), static_cast<std::uint64_t>(trial), point.num_samples);
  std::vector<double> values;
  values.reserve(statistics.size() * w->ms.size());
  const double tau0 = point.model.sample_clock.period_s();
  for (std::size_t si = 0; si < statistics.size(); ++si) {
    estimators::AvarOptions options;
    options.statistic = statistics[si];
    options.sample_clock = point.model.sample_clock;
    options.taus.kind = estimators::TauGridKind::kExplicit;
    for (std::int64_t m : w->ms) options.taus.explicit_taus_s.push_back(static_cast<double>(m) * tau0);
    options.confidence_method = estimators::ConfidenceMethod::kNone;
    estimators::AvarSummary summary;
    if (!estimators::ComputeStatisticValues(options, rate, &summary, &w->allan)) {
      throw std::runtime_error(summary.message);
    }
    std::size_t next = 0;
    for (std::size_t k = 0; k < w->ms.size(); ++k) {
      while (next < summary.points.size() && summary.points[next].m < w->ms[k]) ++next;
      const bool found = next < summary.points.size() && summary.points[next].m == w->ms[k];
      values.push_back(found ? fault_.avar_scale * summary.points[next].value / w->expected[si][k]
                             : std::nan(""));
    }
  }
  return values;
}

std::string AvarBiasExperiment::Question() const {
  return "How biased are the Allan variance estimators on simulated records? Per point and "
         "averaging factor m, the mean over trials of AVAR_hat(m) / E[AVAR_hat(m)], the exact "
         "expectation of the record's estimator (sim::SensorModel::ExpectedAvar, band-limit and "
         "finite record included). Pass: |mean - 1| within a few Monte Carlo standard errors.";
}

bool AvarBiasExperiment::WriteReport(const SweepSpec& spec, const RunSummary& run,
                                     const std::vector<PointStats>& stats,
                                     const ReportContext& context, std::string* why) const {
  std::error_code ec;
  std::filesystem::create_directories(context.output_dir, ec);
  if (ec) {
    *why = "cannot create " + context.output_dir + ": " + ec.message();
    return false;
  }
  std::ostringstream header;
  header << "git_sha: " << context.git_sha << "\nbuild_type: " << context.build_type
         << "\ndate_utc: " << context.date_utc << "\ncommand: " << context.command_line
         << "\nthreads: " << context.threads << "\nranks: " << context.ranks << "\nseed: " << spec.seed
         << "\ntrials: " << spec.trials << "\nfailed_trials: " << run.trials_failed << '\n';
  std::ostringstream csv, md;
  {
    std::istringstream lines(header.str());
    for (std::string line; std::getline(lines, line);) csv << "# " << line << '\n';
  }
  csv << "point,coordinates,column,count,mean,std,standard_error,bias,z\n";
  md << "# " << spec.name << ": Allan variance bias against the exact expectation\n\n"
     << Question() << "\n\n```\n" << header.str() << "```\n\n"
     << "| point | coordinates | column | trials | mean ratio | std | s.e. | bias | z |\n"
     << "|---|---|---|---|---|---|---|---|---|\n";
  for (const PointStats& point : stats) {
    std::string coordinates;
    for (const SweepCoordinate& c : spec.points[static_cast<std::size_t>(point.point)].coordinates) {
      coordinates += coordinates.empty() ? "" : "; ";
      coordinates += c.path + "=" + c.value_text;
    }
    for (const ColumnStats& c : point.columns) {
      const double bias = c.mean - 1.0;
      const double z = bias / c.standard_error;
      csv << point.point << ",\"" << coordinates << "\"," << c.column << ',' << c.count << ','
          << SignificantDigits(c.mean, 17) << ',' << SignificantDigits(c.std, 17) << ',' << SignificantDigits(c.standard_error, 17)
          << ',' << SignificantDigits(bias, 17) << ',' << SignificantDigits(z, 6) << '\n';
      md << "| " << point.point << " | " << coordinates << " | " << c.column << " | " << c.count
         << " | " << SignificantDigits(c.mean, 5) << " | " << SignificantDigits(c.std, 3) << " | "
         << SignificantDigits(c.standard_error, 2) << " | " << SignificantDigits(bias, 2) << " | " << SignificantDigits(z, 2) << " |\n";
    }
  }
  const std::string base = context.output_dir + "/" + spec.name;
  return WriteFileAtomically(base + ".csv", csv.str(), why) && WriteFileAtomically(base + ".md", md.str(), why);
}

}  // namespace allanlab::experiments
