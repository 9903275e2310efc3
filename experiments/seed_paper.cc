#include "experiments/seed_paper.h"

#include <cmath>
#include <limits>
#include <set>
#include <sstream>
#include <stdexcept>
#include <type_traits>
#include <variant>

#include "estimators/avar.h"
#include "estimators/confidence.h"
#include "estimators/fit/avar_curve.h"
#include "estimators/fit/bandwidth_estimate.h"
#include "estimators/fit/fit_model.h"
#include "estimators/fit/noise_coefficient.h"
#include "estimators/fit/slope_method.h"
#include "estimators/tau_grid.h"
#include "experiments/coefficient_trial.h"
#include "experiments/report_files.h"

namespace allanlab::experiments {
namespace {

using estimators::Coefficient;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kRadPerSToDegPerH = 180.0 / M_PI * 3600.0;
// sqrt(2 ln2 / pi): the flicker floor of ADEV per unit B (IEEE 952).
const double kFloorFactor = std::sqrt(2.0 * std::log(2.0) / M_PI);

// The scalar columns, in row order; the per-tau ones follow.
const char* const kScalarColumns[] = {
    "N_curve/paper",        // sigma(1 s) read off the curve / 60 [deg/sqrt(h)]
    "N_curve_ratio/paper",  // ... / true N
    "N_line/slope",         // from the -1/2 line [deg/sqrt(h)]
    "N_line_ratio/slope",
    "N_found/slope",
    "sigma_min/curve",      // [deg/h]
    "tau_min/curve",        // [s]
    "B_min/paper",          // sigma_min / 0.6643 [deg/h]
    "B_min_ratio/paper",    // ... / true B
    "B_min_ratio_floor/paper",  // ... / sqrt(B^2 + 2.617 N K)
    "B_found/slope",
    "fc_first_order/inflection",  // 0.301 / tau_peak [Hz]
    "fc_ratio/inflection",        // ... / true cutoff
    "fc_paper_rule/inflection",   // 1 / (2 pi tau_peak) [Hz]: "inflection tau = time constant"
    "peak_tau/inflection",        // [s]
    "fc_found/inflection",
    // The paper's own procedure (its eqs. 1-2): non-overlapping clusters, L = T/M of them,
    // M = 1, 2, 4, ... while L >= 2, B from the lowest point of that curve.
    "B_min/paper_procedure",         // [deg/h]
    "B_min_ratio/paper_procedure",
    "tau_min/paper_procedure",       // [s]
    // The same with L >= 9 clusters (the paper's error formula 100/sqrt(2(L-1)) <= 25 %).
    "B_min_ratio/paper_procedure_9_clusters",
    "fc_paper_literal/inflection",   // 1 / tau_peak [Hz]: "100 Hz, time constant 10 ms"
    // The correct estimate: `allanlab fit`'s defaults on the octave OAVAR curve at the taus the
    // band-limit leaves unbiased (coefficient_trial.h), with its profile-likelihood intervals.
    "N_fit_ratio/fit", "N_fit_in_ci68.3/fit", "N_fit_in_ci95/fit",
    "B_fit_ratio/fit", "B_fit_in_ci68.3/fit", "B_fit_in_ci95/fit",
    "fit_failed/fit",
};

std::string MColumn(std::string_view prefix, std::int64_t m) {
  std::ostringstream out;
  out << prefix << "/overlapping/m=" << m;
  return out.str();
}

// The paper's Allan deviation (its eq. 2: non-overlapping cluster means, L = floor(N/M)), in the
// record's unit; NaN with fewer than 2 clusters.
double PaperAllanDeviation(const std::vector<double>& rate, std::int64_t m) {
  const std::int64_t clusters = static_cast<std::int64_t>(rate.size()) / m;
  if (clusters < 2) return kNaN;
  double previous = 0.0, sum = 0.0;
  for (std::int64_t l = 0; l < clusters; ++l) {
    double mean = 0.0;
    for (std::int64_t i = 0; i < m; ++i) mean += rate[static_cast<std::size_t>(l * m + i)];
    mean /= static_cast<double>(m);
    if (l > 0) sum += (mean - previous) * (mean - previous);
    previous = mean;
  }
  return std::sqrt(sum / (2.0 * static_cast<double>(clusters - 1)));
}

// The lowest paper Allan deviation [deg/h] and its tau over M = 2^k with >= min_clusters.
void PaperMinimum(const std::vector<double>& rate, double tau0, std::int64_t min_clusters,
                  double* sigma_deg_per_h, double* tau_s) {
  *sigma_deg_per_h = kNaN;
  *tau_s = kNaN;
  const auto n = static_cast<std::int64_t>(rate.size());
  for (std::int64_t m = 1; n / m >= min_clusters; m *= 2) {
    const double sigma = PaperAllanDeviation(rate, m) * kRadPerSToDegPerH;
    if (!(sigma >= *sigma_deg_per_h)) {
      *sigma_deg_per_h = sigma;
      *tau_s = static_cast<double>(m) * tau0;
    }
  }
}

struct PointCache {
  int point = -1;
  std::vector<std::int64_t> ms;
  std::vector<double> expected;
  SeedPaperTruth truth;
};

class Workspace : public TrialWorkspace {
 public:
  PointCache cache;
};

// `allanlab fit`'s defaults on the octave OAVAR curve from the shortest tau the band-limit leaves
// unbiased (coefficient_trial.h): N and B against the truth, with their interval coverage.
void AppendFitColumns(const SweepPoint& point, const std::vector<double>& rate,
                      const SeedPaperTruth& truth, double injected, std::vector<double>* row) {
  estimators::AvarOptions options;
  options.statistic = estimators::Statistic::kAllanOverlapping;
  options.sample_clock = point.model.sample_clock;
  options.taus.kind = estimators::TauGridKind::kOctave;
  estimators::AvarSummary summary;
  if (!estimators::ComputeAvar(options, rate, &summary)) throw std::runtime_error(summary.message);
  std::vector<std::int64_t> ms;
  for (const estimators::AvarPoint& p : summary.points) ms.push_back(p.m);
  const std::int64_t min_m =
      SmallestFitAveragingFactor(point.model, point.num_samples, ms);
  const estimators::AvarCurve curve = estimators::CurveFromSummary(summary, min_m);
  estimators::ModelFitOptions fit;
  estimators::ModelFitSummary m;
  const bool ok = curve.size() >= 2 && estimators::FitModel(fit, curve, &m);
  const auto append = [&](Coefficient c, double truth_datasheet) {
    const estimators::CoefficientEstimate& e = m.fit.at(c);
    const double truth_si = estimators::FromDatasheetUnit(c, truth_datasheet);
    if (!ok || !(truth_si > 0.0)) {
      row->insert(row->end(), {kNaN, kNaN, kNaN});
      return;
    }
    const double value = injected * (e.fitted ? e.value_si : 0.0);
    row->push_back(value / truth_si);
    for (const auto* r : {&e.interval68_si, &e.interval95_si}) {
      row->push_back(e.has_intervals ? ((*r)[0] <= truth_si && truth_si <= (*r)[1] ? 1.0 : 0.0) : kNaN);
    }
  };
  append(Coefficient::kN, truth.n_deg_per_sqrt_h);
  append(Coefficient::kB, truth.b_deg_per_h);
  row->push_back(ok ? 0.0 : 1.0);
}

}  // namespace

SeedPaperTruth TruthOf(const sim::SensorModel& model) {
  double n_si = 0.0, b_si = 0.0, k_si = 0.0;
  for (const sim::NoiseTerm& term : model.terms) {
    std::visit(
        [&](const auto& t) {
          using T = std::remove_cvref_t<decltype(t)>;
          if constexpr (std::is_same_v<T, sim::WhiteRateNoise>) n_si += t.arw_rad_per_sqrt_s;
          if constexpr (std::is_same_v<T, sim::FlickerNoise>) b_si += t.bias_instability_rad_per_s;
          if constexpr (std::is_same_v<T, sim::RandomWalkRate>) k_si += t.rrw_rad_per_s_per_sqrt_s;
        },
        term);
  }
  SeedPaperTruth truth;
  truth.n_deg_per_sqrt_h = estimators::ToDatasheetUnit(Coefficient::kN, n_si);
  truth.b_deg_per_h = estimators::ToDatasheetUnit(Coefficient::kB, b_si);
  truth.k_deg_per_h_per_sqrt_h = estimators::ToDatasheetUnit(Coefficient::kK, k_si);
  truth.cutoff_hz = model.band_limit.enabled() ? model.band_limit.cutoff_hz : 0.0;
  // docs/theory.md §4.2: min over tau of N^2/tau + 0.4413 B^2 + K^2 tau / 3 (SI, consistent units).
  const double floor_si = std::sqrt(b_si * b_si + (2.0 / std::sqrt(3.0)) * n_si * k_si /
                                                       (kFloorFactor * kFloorFactor));
  truth.b_floor_deg_per_h = estimators::ToDatasheetUnit(Coefficient::kB, floor_si);
  return truth;
}

std::vector<std::int64_t> SeedPaperAveragingFactors(const SweepSpec& spec,
                                                    const SweepPoint& point) {
  estimators::TauGridOptions grid;
  std::string why;
  if (!estimators::TauGridOptions::Parse(spec.taus, &grid, &why)) {
    throw std::invalid_argument("taus: " + why);
  }
  std::set<std::int64_t> ms;
  for (std::int64_t m : estimators::CandidateAveragingFactors(grid, point.model.sample_clock.period_s(),
                                                              point.num_samples / 2)) {
    if (m >= 1) ms.insert(m);
  }
  const auto one_second = static_cast<std::int64_t>(std::llround(point.model.sample_clock.rate_hz()));
  if (one_second >= 1 && one_second <= point.num_samples / 2) ms.insert(one_second);
  if (ms.size() < 3) throw std::invalid_argument("fewer than 3 averaging factors");
  return {ms.begin(), ms.end()};
}

std::vector<std::string> SeedPaperDriver::Columns(const SweepSpec& spec,
                                                  const SweepPoint& point) const {
  std::vector<std::string> columns(std::begin(kScalarColumns), std::end(kScalarColumns));
  for (std::int64_t m : SeedPaperAveragingFactors(spec, point)) {
    columns.push_back(MColumn("ratio", m));
    for (double level : spec.confidence_levels) {
      columns.push_back(MColumn("in_ci" + SignificantDigits(100.0 * level, 3) + "/gr", m));
    }
  }
  return columns;
}

std::unique_ptr<TrialWorkspace> SeedPaperDriver::MakeWorkspace() const {
  return std::make_unique<Workspace>();
}

std::vector<double> SeedPaperDriver::Run(const SweepSpec& spec, const SweepPoint& point,
                                         std::int64_t trial, TrialWorkspace* workspace) const {
  auto* ws = dynamic_cast<Workspace*>(workspace);
  Workspace local;
  if (!ws) ws = &local;
  PointCache& cache = ws->cache;
  if (cache.point != point.index || cache.ms.empty()) {
    cache.point = point.index;
    cache.ms = SeedPaperAveragingFactors(spec, point);
    cache.expected = point.model.ExpectedAvar(
        cache.ms, sim::RecordShape{point.num_samples, sim::AvarEstimatorKind::kOverlapping});
    cache.truth = TruthOf(point.model);
  }
  const SeedPaperTruth& truth = cache.truth;
  const double tau0 = point.model.sample_clock.period_s();
  const std::vector<double> rate = point.model.Generate(
      PointSeed(spec.seed, point.index), static_cast<std::uint64_t>(trial), point.num_samples);

  estimators::AvarOptions options;
  options.statistic = estimators::Statistic::kAllanOverlapping;
  options.sample_clock = point.model.sample_clock;
  options.taus.kind = estimators::TauGridKind::kExplicit;
  for (std::int64_t m : cache.ms) options.taus.explicit_taus_s.push_back(static_cast<double>(m) * tau0);
  options.confidence_method = estimators::ConfidenceMethod::kGreenhallRiley;
  estimators::AvarSummary summary;
  if (!estimators::ComputeAvar(options, rate, &summary)) throw std::runtime_error(summary.message);
  for (estimators::AvarPoint& p : summary.points) p.value *= fault_.avar_scale;

  const estimators::AvarCurve curve = estimators::CurveFromSummary(summary);
  std::string why;
  if (!curve.IsValid(&why)) throw std::runtime_error("curve: " + why);

  const auto ratio = [](double v, double truth_value) {
    return truth_value > 0.0 && std::isfinite(v) ? v / truth_value : kNaN;
  };
  double sigma_1s = kNaN, sigma_min = kNaN, tau_min = kNaN;
  const auto one_second = static_cast<std::int64_t>(std::llround(point.model.sample_clock.rate_hz()));
  for (std::size_t i = 0; i < curve.size(); ++i) {
    const double adev = std::sqrt(curve.avar[i]) * kRadPerSToDegPerH;
    if (curve.m[i] == one_second) sigma_1s = adev;
    if (!(adev >= sigma_min)) {
      sigma_min = adev;
      tau_min = curve.tau_s[i];
    }
  }
  const estimators::SlopeMethodResult slopes = estimators::ReadSlopes(curve);
  const estimators::SlopeReading& n_line = slopes.at(Coefficient::kN);
  const estimators::SlopeReading& b_line = slopes.at(Coefficient::kB);
  const double injected = fault_.coefficient_scale;
  const double n_curve = injected * sigma_1s / 60.0;
  const double n_line_value =
      n_line.found ? injected * estimators::ToDatasheetUnit(Coefficient::kN, n_line.value_si)
                   : kNaN;
  const double b_min = injected * sigma_min / kFloorFactor;
  const estimators::BandwidthEstimate bandwidth = estimators::EstimateBandwidth(curve);
  double paper_sigma = kNaN, paper_tau = kNaN, paper9_sigma = kNaN, paper9_tau = kNaN;
  PaperMinimum(rate, tau0, 2, &paper_sigma, &paper_tau);
  PaperMinimum(rate, tau0, 9, &paper9_sigma, &paper9_tau);
  const double b_paper = injected * paper_sigma / kFloorFactor;
  const double b_paper9 = injected * paper9_sigma / kFloorFactor;
  const double fc = bandwidth.found ? bandwidth.cutoff_first_order_hz : kNaN;
  const double peak = bandwidth.found ? bandwidth.peak_tau_s : kNaN;

  std::vector<double> row = {
      n_curve,
      ratio(n_curve, truth.n_deg_per_sqrt_h),
      n_line_value,
      ratio(n_line_value, truth.n_deg_per_sqrt_h),
      n_line.found ? 1.0 : 0.0,
      sigma_min,
      tau_min,
      b_min,
      ratio(b_min, truth.b_deg_per_h),
      ratio(b_min, truth.b_floor_deg_per_h),
      b_line.found ? 1.0 : 0.0,
      fc,
      ratio(fc, truth.cutoff_hz),
      bandwidth.found ? 1.0 / (2.0 * M_PI * peak) : kNaN,
      peak,
      bandwidth.found ? 1.0 : 0.0,
      b_paper,
      ratio(b_paper, truth.b_deg_per_h),
      paper_tau,
      ratio(b_paper9, truth.b_deg_per_h),
      bandwidth.found ? 1.0 / peak : kNaN,
  };
  AppendFitColumns(point, rate, truth, injected, &row);
  for (std::size_t i = 0; i < cache.ms.size(); ++i) {
    const estimators::AvarPoint* p = nullptr;
    for (const auto& candidate : summary.points) {
      if (candidate.m == cache.ms[i]) p = &candidate;
    }
    const double expected = cache.expected[i];
    row.push_back(p && expected > 0.0 ? p->value / expected : kNaN);
    for (double level : spec.confidence_levels) {
      if (!p || !(p->edf > 0.0) || !(expected > 0.0)) {
        row.push_back(kNaN);
        continue;
      }
      const estimators::Interval ci = estimators::PointInterval(summary, *p, level);
      row.push_back(ci.low <= expected && expected <= ci.high ? 1.0 : 0.0);
    }
  }
  return row;
}

}  // namespace allanlab::experiments
