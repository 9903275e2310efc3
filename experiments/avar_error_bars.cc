#include "experiments/avar_error_bars.h"

#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <type_traits>
#include <variant>

#include "estimators/avar.h"
#include "estimators/confidence.h"
#include "estimators/exact_edf.h"
#include "estimators/tau_grid.h"
#include "experiments/report_files.h"

namespace allanlab::experiments {
namespace {

using estimators::Statistic;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string MKey(std::int64_t m) { return "m=" + std::to_string(m); }

std::string LevelKey(double level) { return "in_ci" + SignificantDigits(100.0 * level, 3); }

const char* const kEdfKinds[] = {"simple", "gr", "exact"};

std::string Column(std::string_view quantity, std::string_view est, std::int64_t m) {
  std::string out(quantity);
  out += '/';
  out += est;
  out += '/';
  out += MKey(m);
  return out;
}

std::string CoverageColumn(double level, std::string_view kind, std::string_view est,
                           std::int64_t m) {
  std::string out = LevelKey(level);
  out += '/';
  out += kind;
  out += '/';
  out += Column("", est, m).substr(1);
  return out;
}

sim::AvarEstimatorKind KindOf(Statistic s) {
  return s == Statistic::kAllanNonOverlapping ? sim::AvarEstimatorKind::kNonOverlapping
                                              : sim::AvarEstimatorKind::kOverlapping;
}

// What every trial of a point shares: expectations and exact EDFs (computed once per thread).
struct PointTheory {
  int point = -1;
  std::vector<std::int64_t> ms;
  std::vector<std::vector<double>> expected;   // [statistic][m]: normaliser of the ratio
  std::vector<std::vector<double>> exact_edf;  // [statistic][m]: NaN when not available
};

class Workspace : public TrialWorkspace {
 public:
  PointTheory theory;
};

// True when every term with a share in the AVAR is one sim::SensorModel::GaussianAutocovariance
// describes, and there are no output quantizers.
bool GaussianOnly(const SweepPoint& point) {
  if (point.model.angle_quantizer || point.model.rate_quantizer) return false;
  const double tau0 = point.model.sample_clock.period_s();
  const sim::RecordShape shape{std::max<std::int64_t>(point.num_samples, 2),
                               sim::AvarEstimatorKind::kOverlapping};
  for (const sim::NoiseTerm& term : point.model.terms) {
    const std::string_view id = sim::TermId(term);
    const bool gaussian = id == "quantization" || id == "arw" || id == "bias_instability" ||
                          id == "bias_instability_gm_sum" || id == "rrw" || id == "gauss_markov";
    const double level =
        std::visit([&](const auto& t) { return t.ExpectedAvar(1, tau0, shape); }, term);
    if (!gaussian && level > 0.0) return false;
  }
  return true;
}

PointTheory MakeTheory(const SweepSpec& spec, const SweepPoint& point) {
  PointTheory theory;
  theory.point = point.index;
  theory.ms = ErrorBarAveragingFactors(spec, point);
  // The exact EDF describes the model's Gaussian part only, so a model with a non-Gaussian term
  // (ramp, harmonic, ...) gets none. (Testing R(0) > 0 instead would also drop lone flicker and
  // random walk, whose generalised autocovariances start at R(0) = 0.)
  const bool gaussian = GaussianOnly(point);
  for (Statistic s : ErrorBarStatistics()) {
    const sim::RecordShape shape{point.num_samples, KindOf(s)};
    theory.expected.push_back(point.model.ExpectedAvar(theory.ms, shape));
    std::vector<double> edf(theory.ms.size(), kNaN);
    if (estimators::HasExactMoments(s) && gaussian) {
      const std::vector<estimators::AvarMoments> exact =
          estimators::ModelStatisticMoments(point.model, s, theory.ms, point.num_samples);
      for (std::size_t i = 0; i < edf.size(); ++i) {
        const double e = exact[i].edf();
        if (e > 0.0 && std::isfinite(e)) edf[i] = e;
      }
    }
    theory.exact_edf.push_back(std::move(edf));
  }
  return theory;
}

}  // namespace

const std::vector<Statistic>& ErrorBarStatistics() {
  static const std::vector<Statistic> kStatistics = {
      Statistic::kAllanNonOverlapping, Statistic::kAllanOverlapping, Statistic::kModifiedAllan,
      Statistic::kHadamardOverlapping, Statistic::kTotal};
  return kStatistics;
}

bool HasExactTheory(Statistic s) {
  return s == Statistic::kAllanNonOverlapping || s == Statistic::kAllanOverlapping;
}

std::vector<std::int64_t> ErrorBarAveragingFactors(const SweepSpec& spec,
                                                   const SweepPoint& point) {
  estimators::TauGridOptions grid;
  std::string why;
  if (!estimators::TauGridOptions::Parse(spec.taus, &grid, &why)) {
    throw std::invalid_argument("taus: " + why);
  }
  const double tau0 = point.model.sample_clock.period_s();
  std::vector<std::int64_t> ms;
  for (std::int64_t m : estimators::CandidateAveragingFactors(grid, tau0, point.num_samples / 4)) {
    if (m >= 1) ms.push_back(m);
  }
  if (ms.empty()) throw std::invalid_argument("no averaging factor with at least 4 clusters");
  return ms;
}

std::string NoiseLabel(const SweepPoint& point) {
  const double tau0 = point.model.sample_clock.period_s();
  const sim::RecordShape shape{std::max<std::int64_t>(point.num_samples, 2),
                               sim::AvarEstimatorKind::kOverlapping};
  std::vector<std::string> ids;
  for (const sim::NoiseTerm& term : point.model.terms) {
    const double level =
        std::visit([&](const auto& t) { return t.ExpectedAvar(1, tau0, shape); }, term);
    if (!(level > 0.0)) continue;
    const std::string_view id = sim::TermId(term);
    if (id == "quantization") ids.push_back("Q");
    else if (id == "arw") ids.push_back("N");
    else if (id == "bias_instability") ids.push_back("B");
    else if (id == "rrw") ids.push_back("K");
    else if (id == "ramp") ids.push_back("R");
    else ids.push_back(std::string(id));
  }
  std::string joined;
  for (const std::string& id : ids) {
    if (!joined.empty()) joined += '+';
    joined += id;
  }
  std::string name;
  if (ids.size() > 1) {
    name = "composite";
  } else if (ids.empty()) {
    name = "no noise";
  } else {
    const std::string& id = ids[0];
    name = id == "Q"   ? "quantization"
           : id == "N" ? "white"
           : id == "B" ? "flicker"
           : id == "K" ? "random walk"
           : id == "R" ? "ramp"
                       : id;
  }
  std::string label = name + " (" + joined;
  if (point.model.band_limit.enabled()) {
    label = "band-limited " + label + ", " +
            (point.model.band_limit.kind == sim::LowPassKind::kFirstOrder ? "first-order "
                                                                          : "Butterworth-2 ") +
            SignificantDigits(point.model.band_limit.cutoff_hz, 4) + " Hz";
  }
  return label + ")";
}

std::vector<std::string> AvarErrorBarsDriver::Columns(const SweepSpec& spec,
                                                      const SweepPoint& point) const {
  const std::vector<std::int64_t> ms = ErrorBarAveragingFactors(spec, point);
  std::vector<std::string> columns;
  for (Statistic s : ErrorBarStatistics()) {
    const std::string_view est = estimators::StatisticId(s);
    for (std::int64_t m : ms) {
      columns.push_back(Column("ratio", est, m));
      for (const char* kind : kEdfKinds) columns.push_back(Column(std::string("edf_") + kind, est, m));
      for (double level : spec.confidence_levels) {
        for (const char* kind : kEdfKinds) columns.push_back(CoverageColumn(level, kind, est, m));
      }
    }
  }
  return columns;
}

std::unique_ptr<TrialWorkspace> AvarErrorBarsDriver::MakeWorkspace() const {
  return std::make_unique<Workspace>();
}

std::vector<double> AvarErrorBarsDriver::Run(const SweepSpec& spec, const SweepPoint& point,
                                             std::int64_t trial,
                                             TrialWorkspace* workspace) const {
  auto* ws = dynamic_cast<Workspace*>(workspace);
  PointTheory local;
  PointTheory* theory = ws ? &ws->theory : &local;
  if (theory->point != point.index || theory->ms.empty()) *theory = MakeTheory(spec, point);
  const std::vector<std::int64_t>& ms = theory->ms;

  const std::vector<double> rate = point.model.Generate(
      PointSeed(spec.seed, point.index), static_cast<std::uint64_t>(trial), point.num_samples);
  const double tau0 = point.model.sample_clock.period_s();

  std::vector<double> row;
  const auto& statistics = ErrorBarStatistics();
  for (std::size_t si = 0; si < statistics.size(); ++si) {
    const Statistic s = statistics[si];
    estimators::AvarOptions options;
    options.statistic = s;
    options.sample_clock = point.model.sample_clock;
    options.taus.kind = estimators::TauGridKind::kExplicit;
    for (std::int64_t m : ms) options.taus.explicit_taus_s.push_back(static_cast<double>(m) * tau0);
    options.confidence_method = estimators::ConfidenceMethod::kGreenhallRiley;
    estimators::AvarSummary summary;
    if (!estimators::ComputeAvar(options, rate, &summary)) {
      throw std::runtime_error(std::string(estimators::StatisticId(s)) + ": " + summary.message);
    }
    for (estimators::AvarPoint& p : summary.points) p.value *= fault_.avar_scale;
    for (std::size_t mi = 0; mi < ms.size(); ++mi) {
      const estimators::AvarPoint* p = nullptr;
      for (const auto& candidate : summary.points) {
        if (candidate.m == ms[mi]) p = &candidate;
      }
      const double expected = theory->expected[si][mi];
      const double value = p ? p->value : kNaN;
      const double edf[3] = {
          estimators::SimpleEdf(point.num_samples / ms[mi]),
          p && p->edf > 0.0 ? p->edf : kNaN,
          theory->exact_edf[si][mi],
      };
      row.push_back(expected > 0.0 ? value / expected : kNaN);
      for (double e : edf) row.push_back(e);
      for (double level : spec.confidence_levels) {
        for (double e : edf) {
          if (!HasExactTheory(s) || !(expected > 0.0) || !(e > 0.0) || !std::isfinite(value)) {
            row.push_back(kNaN);
            continue;
          }
          const estimators::Interval ci = estimators::ChiSquareInterval(value, e, level);
          row.push_back(ci.low <= expected && expected <= ci.high ? 1.0 : 0.0);
        }
      }
    }
  }
  return row;
}

}  // namespace allanlab::experiments
