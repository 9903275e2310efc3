#include "experiments/coefficient_trial.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <stdexcept>
#include <type_traits>
#include <variant>

#include <boost/math/special_functions/erf.hpp>

#include "estimators/avar.h"
#include "estimators/fit/fit_avar_model.h"
#include "estimators/fit/fit_model.h"
#include "estimators/fit/slope_method.h"

namespace allanlab::experiments {
namespace {

using estimators::Coefficient;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

int Index(Coefficient c) { return static_cast<int>(c); }


// "default": what `allanlab fit` does by default on the point's curve (GLS, Q,N,B,K,R with the
// subset choice, profile-likelihood intervals), scored by its intervals rather than by sigma.
constexpr const char* kDefaultMethod = "default";

bool ParseMethod(const std::string& name, estimators::FitMethod* method) {
  if (name == kDefaultMethod) *method = estimators::FitMethod::kGls;
  else if (name == "wls") *method = estimators::FitMethod::kWls;
  else if (name == "log_wls") *method = estimators::FitMethod::kLogWls;
  else if (name == "gls") *method = estimators::FitMethod::kGls;
  else if (name == "slope") *method = estimators::FitMethod::kSlope;
  else return false;
  return true;
}

// Everything about a point that does not change from trial to trial.
struct PointPlan {
  estimators::TauGridOptions grid;
  std::int64_t min_m = 1;
  std::int64_t max_m = 0;
  TrueCoefficients truth;
  std::vector<Coefficient> fit_terms;  // what the fits are asked for
  std::vector<Coefficient> compared;   // fit_terms present in the truth
  std::vector<std::string> methods;
  std::vector<double> z;               // normal quantile of each confidence level
  bool slope_read_target = false;      // rel_err_read/slope/B columns
  std::vector<std::string> columns;
};

PointPlan MakePlan(const SweepSpec& spec, const SweepPoint& point) {
  PointPlan plan;
  std::string why;
  if (!estimators::TauGridOptions::Parse(spec.taus, &plan.grid, &why)) {
    throw std::invalid_argument("taus: " + why);
  }
  plan.truth = TrueCoefficientsOf(point.model);
  if (spec.fit_terms.empty()) {
    for (Coefficient c : estimators::kAllCoefficients) {
      if (plan.truth.has(c)) plan.fit_terms.push_back(c);
    }
  } else {
    for (const std::string& id : spec.fit_terms) {
      Coefficient c;
      if (!estimators::ParseCoefficient(id, &c)) throw std::invalid_argument("fit term " + id);
      plan.fit_terms.push_back(c);
    }
  }
  for (Coefficient c : plan.fit_terms) {
    if (plan.truth.has(c)) plan.compared.push_back(c);
  }
  plan.methods = MethodsOf(spec);
  for (double level : spec.confidence_levels) {
    plan.z.push_back(std::sqrt(2.0) * boost::math::erf_inv(level));
  }
  const FitAveragingWindow window = FitWindowOf(spec, point);
  plan.min_m = window.min_m;
  plan.max_m = window.max_m;
  plan.slope_read_target = plan.truth.has(Coefficient::kN) && plan.truth.has(Coefficient::kB) &&
                           plan.truth.has(Coefficient::kK);

  for (const std::string& method : plan.methods) {
    const bool fit = method != "slope";
    if (fit) {
      plan.columns.push_back("failed/" + method);
      plan.columns.push_back("converged/" + method);
    }
    for (Coefficient c : plan.compared) {
      const std::string suffix = "/" + method + "/" + std::string(estimators::CoefficientId(c));
      plan.columns.push_back("rel_err" + suffix);
      plan.columns.push_back("sq_rel_err" + suffix);
      plan.columns.push_back("missing" + suffix);
      if (fit) {
        plan.columns.push_back("rel_sigma" + suffix);
        for (double level : spec.confidence_levels) plan.columns.push_back(CoverageColumnName(level) + suffix);
      }
      if (!fit && c == Coefficient::kB && plan.slope_read_target) {
        plan.columns.push_back("rel_err_read" + suffix);
        plan.columns.push_back("sq_rel_err_read" + suffix);
      }
    }
  }
  return plan;
}

class Workspace : public TrialWorkspace {
 public:
  const PointPlan& PlanFor(const SweepSpec& spec, const SweepPoint& point) {
    if (spec_ != &spec) {
      plans_.clear();
      spec_ = &spec;
    }
    auto it = plans_.find(point.index);
    if (it == plans_.end()) it = plans_.emplace(point.index, MakePlan(spec, point)).first;
    return it->second;
  }

 private:
  const SweepSpec* spec_ = nullptr;
  std::map<int, PointPlan> plans_;
};

// Appends the columns of one coefficient for an estimate (value, sigma; has_sigma false for the
// slope method), in MakePlan's order.
void AppendCoefficient(const PointPlan& plan, Coefficient c, bool found, double value,
                       bool has_sigma, double sigma, const InjectedFault& fault,
                       std::vector<double>* row) {
  const double truth = plan.truth.at(c);
  value *= fault.coefficient_scale;
  const double rel = found ? value / truth - 1.0 : kNaN;
  row->push_back(rel);
  row->push_back(rel * rel);
  row->push_back(found ? 0.0 : 1.0);
  if (has_sigma) {
    row->push_back(found ? sigma / truth : kNaN);
    for (double z : plan.z) {
      row->push_back(found ? (std::abs(value - truth) <= z * sigma ? 1.0 : 0.0) : kNaN);
    }
  }
}

// The same columns for the default method: covered when the truth lies in the profile-likelihood
// interval of the level (68.3 % or 95 %); a term not determined has the interval from 0 to its
// profile end at that level.
void AppendProfileCoefficient(const PointPlan& plan, Coefficient c, bool ok,
                              const estimators::CoefficientEstimate& e, std::vector<double>* row) {
  const double truth = plan.truth.at(c);
  const double value = e.fitted ? e.value_si : 0.0;
  const double rel = ok ? value / truth - 1.0 : kNaN;
  row->push_back(rel);
  row->push_back(rel * rel);
  row->push_back(ok ? 0.0 : 1.0);
  row->push_back(ok ? (e.fitted ? e.sigma_si : 0.0) / truth : kNaN);
  for (double z : plan.z) {
    const bool wide = z > 1.5;  // the 95 % level (z 1.96) or the 68.3 % one (z 1.0)
    const std::array<double, 2>& r = wide ? e.interval95_si : e.interval68_si;
    row->push_back(ok && e.has_intervals ? (r[0] <= truth && truth <= r[1] ? 1.0 : 0.0) : kNaN);
  }
}

// The curve a slope-method user reads: the plotted one, m <= N/8 (as `allanlab simulate --plot`
// draws it). With the estimates out to N/2 (EDF ~ 1) the "minimum" is nearly always the last,
// lowest-EDF point, and B comes out 80 % low on a 24 h mg25_mems record.
estimators::AvarCurve SlopeMethodCurve(const estimators::AvarCurve& curve) {
  estimators::AvarCurve c = curve;
  c.m.clear();
  c.tau_s.clear();
  c.avar.clear();
  c.edf.clear();
  for (std::size_t k = 0; k < curve.size(); ++k) {
    if (curve.m[k] > curve.num_samples / kSlopeMethodMaxFraction) continue;
    c.m.push_back(curve.m[k]);
    c.tau_s.push_back(curve.tau_s[k]);
    c.avar.push_back(curve.avar[k]);
    c.edf.push_back(curve.edf[k]);
  }
  return c;
}

}  // namespace

TrueCoefficients TrueCoefficientsOf(const sim::SensorModel& model) {
  TrueCoefficients t;
  std::array<double, 5> squares = {};
  for (const sim::NoiseTerm& term : model.terms) {
    std::visit(
        [&](const auto& x) {
          using T = std::remove_cvref_t<decltype(x)>;
          auto add = [&](Coefficient c, double v) {
            squares[Index(c)] += v * v;
            t.present[Index(c)] = true;
          };
          if constexpr (std::is_same_v<T, sim::QuantizationNoise>) add(Coefficient::kQ, x.q_rad);
          else if constexpr (std::is_same_v<T, sim::WhiteRateNoise>) add(Coefficient::kN, x.arw_rad_per_sqrt_s);
          else if constexpr (std::is_same_v<T, sim::FlickerNoise>) add(Coefficient::kB, x.bias_instability_rad_per_s);
          else if constexpr (std::is_same_v<T, sim::RandomWalkRate>) add(Coefficient::kK, x.rrw_rad_per_s_per_sqrt_s);
          else if constexpr (std::is_same_v<T, sim::RateRamp>) add(Coefficient::kR, x.ramp_rad_per_s2);
          else t.unmapped.emplace_back(T::kId);
        },
        term);
  }
  for (int i = 0; i < 5; ++i) {
    t.value_si[i] = std::sqrt(squares[i]);
    if (t.value_si[i] == 0.0) t.present[i] = false;
  }
  return t;
}

double SlopeMethodBTarget(const TrueCoefficients& truth) {
  const double b = truth.at(Coefficient::kB);
  // 2.617 = (2 / sqrt 3) / (2 ln2 / pi), docs/theory.md §4.2.
  const double k = (2.0 / std::sqrt(3.0)) / (2.0 * std::log(2.0) / M_PI);
  return std::sqrt(b * b + k * truth.at(Coefficient::kN) * truth.at(Coefficient::kK));
}

std::int64_t SmallestFitAveragingFactor(const sim::SensorModel& model, std::int64_t num_samples,
                                        const std::vector<std::int64_t>& candidates) {
  if (!model.band_limit.enabled() || candidates.empty()) return 1;
  sim::SensorModel white;
  white.sample_clock = model.sample_clock;
  white.band_limit = model.band_limit;
  sim::WhiteRateNoise unit;
  unit.arw_rad_per_sqrt_s = 1.0;
  white.terms.push_back(unit);
  const sim::RecordShape shape{num_samples, sim::AvarEstimatorKind::kOverlapping};
  const double tau0 = model.sample_clock.period_s();
  for (std::int64_t m : candidates) {
    if (m < 1) continue;
    const double deficit = 1.0 - white.ExpectedAvar(m, shape) / unit.ExpectedAvar(m, tau0, shape);
    // Relative sd of an overlapping white-noise AVAR estimate, sqrt(2 / EDF), EDF ~ 1.5 N/m.
    const double sd = std::sqrt(4.0 * static_cast<double>(m) / (3.0 * static_cast<double>(num_samples)));
    if (std::abs(deficit) <= std::min(kMaxBandLimitDeficit, kMaxBandLimitDeficitInSd * sd)) return m;
  }
  return candidates.back() + 1;  // no tau qualifies: the fits see an empty curve and fail
}

FitAveragingWindow FitWindowOf(const SweepSpec& spec, const SweepPoint& point) {
  estimators::TauGridOptions grid;
  std::string why;
  if (!estimators::TauGridOptions::Parse(spec.taus, &grid, &why)) {
    throw std::invalid_argument("taus: " + why);
  }
  const double tau0 = point.model.sample_clock.period_s();
  const std::vector<std::int64_t> candidates =
      estimators::CandidateAveragingFactors(grid, tau0, point.num_samples / 2);
  FitAveragingWindow window;
  window.min_m = SmallestFitAveragingFactor(point.model, point.num_samples, candidates);
  window.max_m = candidates.empty() ? 0 : candidates.back();
  if (!(spec.fit_tau_max_s > 0.0)) return window;
  // A fixed window: the candidates inside [tau_min, tau_max] (a relative 1e-9 for rounding).
  std::int64_t lo = 0, hi = 0;
  for (std::int64_t m : candidates) {
    const double tau = static_cast<double>(m) * tau0;
    if (tau < spec.fit_tau_min_s * (1.0 - 1e-9) || tau > spec.fit_tau_max_s * (1.0 + 1e-9)) continue;
    if (lo == 0) lo = m;
    hi = m;
  }
  const std::string where = point.model.name + " at " + std::to_string(point.num_samples) + " samples";
  if (lo == 0) throw std::invalid_argument("fit.tau_range holds no tau of the grid (" + where + ")");
  if (lo < window.min_m) {
    throw std::invalid_argument("fit.tau_range starts at " + std::to_string(lo * tau0) +
                                " s, below the shortest tau the band-limit leaves unbiased at " +
                                where + " (" + std::to_string(window.min_m * tau0) + " s)");
  }
  if (hi > point.num_samples / 8) {
    throw std::invalid_argument("fit.tau_range ends at " + std::to_string(hi * tau0) +
                                " s, which leaves fewer than 8 clusters at " + where);
  }
  window.min_m = lo;
  window.max_m = hi;
  return window;
}

std::vector<std::string> MethodsOf(const SweepSpec& spec) {
  if (!spec.fit_methods.empty()) return spec.fit_methods;
  return {std::begin(kFitMethodNames), std::end(kFitMethodNames)};
}

std::vector<Coefficient> ComparedCoefficients(const SweepSpec& spec, const SweepPoint& point) {
  return MakePlan(spec, point).compared;
}

std::vector<std::string> CoefficientTrialDriver::Columns(const SweepSpec& spec,
                                                         const SweepPoint& point) const {
  return MakePlan(spec, point).columns;
}

std::unique_ptr<TrialWorkspace> CoefficientTrialDriver::MakeWorkspace() const {
  return std::make_unique<Workspace>();
}

std::vector<double> CoefficientTrialDriver::Run(const SweepSpec& spec, const SweepPoint& point,
                                                std::int64_t trial,
                                                TrialWorkspace* workspace) const {
  const PointPlan& plan = static_cast<Workspace*>(workspace)->PlanFor(spec, point);
  const std::vector<double> record = point.model.Generate(PointSeed(spec.seed, point.index),
                                                          static_cast<std::uint64_t>(trial),
                                                          point.num_samples);
  estimators::AvarOptions options;
  options.statistic = estimators::Statistic::kAllanOverlapping;
  options.taus = plan.grid;
  options.sample_clock = point.model.sample_clock;
  estimators::AvarSummary avar;
  if (!estimators::ComputeAvar(options, record, &avar)) {
    throw std::runtime_error("avar: " + avar.message);
  }
  for (estimators::AvarPoint& p : avar.points) p.value *= fault_.avar_scale;
  const estimators::AvarCurve curve = estimators::CurveFromSummary(avar, plan.min_m, plan.max_m);

  std::vector<double> row;
  row.reserve(plan.columns.size());
  for (const std::string& name : plan.methods) {
    estimators::FitMethod method;
    if (!ParseMethod(name, &method)) throw std::invalid_argument("unknown fit method " + name);
    if (method == estimators::FitMethod::kSlope) {
      const estimators::AvarCurve plotted = SlopeMethodCurve(curve);
      std::string why;
      const bool usable = plotted.size() >= 2 && plotted.IsValid(&why);
      estimators::SlopeMethodResult slope;
      if (usable) slope = estimators::ReadSlopes(plotted);
      for (Coefficient c : plan.compared) {
        const auto& r = slope.at(c);
        const bool found = usable && r.found;
        AppendCoefficient(plan, c, found, r.value_si, false, 0.0, fault_, &row);
        if (c == Coefficient::kB && plan.slope_read_target) {
          const double read = fault_.coefficient_scale * r.value_si;
          const double rel = found ? read / SlopeMethodBTarget(plan.truth) - 1.0 : kNaN;
          row.push_back(rel);
          row.push_back(rel * rel);
        }
      }
      continue;
    }
    if (name == kDefaultMethod) {
      estimators::ModelFitOptions fit;  // the defaults of `allanlab fit` (band-limit: taus cut above)
      estimators::ModelFitSummary m;
      const bool ok = curve.size() >= 2 && estimators::FitModel(fit, curve, &m);
      row.push_back(ok ? 0.0 : 1.0);
      row.push_back(ok && m.fit.converged ? 1.0 : 0.0);
      for (Coefficient c : plan.compared) AppendProfileCoefficient(plan, c, ok, m.fit.at(c), &row);
      continue;
    }
    estimators::FitOptions fit;
    fit.method = method;
    fit.terms = plan.fit_terms;
    fit.select_terms = false;
    estimators::FitSummary summary;
    const bool ok = curve.size() >= 2 && estimators::FitAvarModel(fit, curve, &summary);
    row.push_back(ok ? 0.0 : 1.0);
    row.push_back(ok && summary.converged ? 1.0 : 0.0);
    for (Coefficient c : plan.compared) {
      const auto& e = summary.at(c);
      const double value = e.fitted ? e.value_si : 0.0;
      const double sigma = e.fitted ? e.sigma_si : 0.0;
      AppendCoefficient(plan, c, ok, value, true, sigma, fault_, &row);
    }
  }
  if (row.size() != plan.columns.size()) throw std::logic_error("coefficient trial: row size");
  return row;
}

std::string CoverageColumnName(double level) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "in_ci%g", level * 100.0);
  return buffer;
}

}  // namespace allanlab::experiments
