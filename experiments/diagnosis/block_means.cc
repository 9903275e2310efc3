#include "experiments/diagnosis/block_means.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <variant>

#include <boost/math/distributions/normal.hpp>
#include <boost/random/normal_distribution.hpp>

#include "experiments/diagnosis/profiled_step.h"
#include "sim/seeding.h"

namespace allanlab::experiments {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kMaxZ = 37.0;  // as the other views' z (gap.cc)
// Lags up to which the band-limit and the quantizers enter the autocovariance exactly; beyond, the
// terms' own (docs/theory.md §6.7).
constexpr std::int64_t kShortLags = std::int64_t{1} << 15;
constexpr std::uint64_t kNullSeed = 0x626c6f636b6d65ULL;
// Draws of the profiled change-point statistic's null (profiled_step.h): fewer than the held
// statistics' (each costs a profile over K), the tail beyond the 20th largest extrapolated alike.
constexpr int kProfiledNullDraws = 1000;

bool IsEvent(const sim::NoiseTerm& t) {
  return std::holds_alternative<sim::BiasStep>(t) || std::holds_alternative<sim::ExponentialDrift>(t);
}

// |z| = Phi^{-1}(1 - p/2), capped as the other views' z.
double ZFromTwoSidedP(double p) {
  if (!(p < 1.0)) return 0.0;
  if (!(p > 0.0)) return kMaxZ;
  return std::min(kMaxZ, -boost::math::quantile(boost::math::normal(), 0.5 * p));
}

// Generalised autocovariance R(0 .. lags-1) of the model's random part (docs/theory.md §6.7).
std::vector<double> RandomPartAutocovariance(const sim::SensorModel& model, std::int64_t lags) {
  sim::SensorModel plain = model;
  plain.band_limit = sim::BandLimit{};
  plain.angle_quantizer.reset();
  plain.rate_quantizer.reset();
  std::vector<double> r = plain.GaussianAutocovariance(lags);
  if (model.band_limit.enabled() || model.angle_quantizer || model.rate_quantizer) {
    const std::vector<double> near = model.GaussianAutocovariance(std::min(lags, kShortLags));
    std::copy(near.begin(), near.end(), r.begin());
  }
  const double tau0 = model.sample_clock.period_s();
  for (const sim::NoiseTerm& t : model.terms) {
    if (const auto* o = std::get_if<sim::Outliers>(&t)) r[0] += o->rate_hz * tau0 * o->size_rad_per_s * o->size_rad_per_s;
  }
  return r;
}

// S(n) = Var(sum of n consecutive samples) = n R(0) + 2 sum_{l=1}^{n-1} (n - l) R(l) at each n of
// `ns` (ascending, each <= r.size()).
std::vector<long double> SumVariance(const std::vector<double>& r, const std::vector<std::int64_t>& ns) {
  std::vector<long double> s(ns.size(), 0.0L);
  long double a = 0.0L, b = 0.0L;  // sum_{l=1}^{n-1} R(l), sum_{l=1}^{n-1} l R(l)
  std::int64_t l = 1;
  for (std::size_t i = 0; i < ns.size(); ++i) {
    for (; l < ns[i]; ++l) {
      a += r[static_cast<std::size_t>(l)];
      b += static_cast<long double>(l) * r[static_cast<std::size_t>(l)];
    }
    const auto n = static_cast<long double>(ns[i]);
    s[i] = ns[i] == 0 ? 0.0L : n * (r[0] + 2.0L * a) - 2.0L * b;
  }
  return s;
}

// D(k) = Var(u_{b+k} - u_b) of block means of m samples, k = 0 .. blocks - 1 (eq. 6.7.2), from
// the generalised autocovariance r (at least blocks m + 1 lags).
std::vector<long double> StructureFunction(const std::vector<double>& r, std::int64_t m, int blocks) {
  std::vector<std::int64_t> ns;
  for (int j = 0; j <= blocks; ++j) ns.push_back(j * m);
  const std::vector<long double> s = SumVariance(r, ns);  // s[j] = S(j m)
  std::vector<long double> d(static_cast<std::size_t>(blocks), 0.0L);
  const auto m2 = static_cast<long double>(m) * static_cast<long double>(m);
  for (int k = 1; k < blocks; ++k) d[k] = (2.0L * s[1] + 2.0L * s[k] - s[k + 1] - s[k - 1]) / m2;
  return d;
}

std::vector<double> CovarianceFromAutocovariance(const std::vector<double>& r, std::int64_t m, int blocks,
                                                 double ramp2_tau2) {
  const std::vector<long double> d = StructureFunction(r, m, blocks);
  std::vector<double> c(static_cast<std::size_t>(blocks - 1));
  for (int k = 0; k + 1 < blocks; ++k) {
    c[k] = static_cast<double>(-d[k] + 0.5L * d[k + 1] + 0.5L * d[std::abs(k - 1)]) + ramp2_tau2;
  }
  return c;
}

double RandomWalkSquared(const sim::SensorModel& model) {
  double k2 = 0.0;
  for (const sim::NoiseTerm& t : model.terms) {
    if (const auto* k = std::get_if<sim::RandomWalkRate>(&t)) k2 += k->rrw_rad_per_s_per_sqrt_s * k->rrw_rad_per_s_per_sqrt_s;
  }
  return k2;
}

double RampSquared(const sim::SensorModel& model) {
  double r2 = 0.0;
  for (const sim::NoiseTerm& t : model.terms) {
    if (const auto* r = std::get_if<sim::RateRamp>(&t)) r2 += r->ramp_rad_per_s2 * r->ramp_rad_per_s2;
  }
  return r2;
}

// Lower Cholesky factor of the Toeplitz matrix with first row c (row-major, n x n); false when not
// positive definite.
bool Cholesky(const std::vector<double>& c, std::vector<double>* l) {
  const std::size_t n = c.size();
  l->assign(n * n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = 0; j <= i; ++j) {
      double sum = c[i - j];
      for (std::size_t k = 0; k < j; ++k) sum -= (*l)[i * n + k] * (*l)[j * n + k];
      if (i == j) {
        if (!(sum > 0.0)) return false;
        (*l)[i * n + i] = std::sqrt(sum);
      } else {
        (*l)[i * n + j] = sum / (*l)[j * n + j];
      }
    }
  }
  return true;
}

// Solves L x = b in place.
void Forward(const std::vector<double>& l, std::vector<double>* x) {
  const std::size_t n = x->size();
  for (std::size_t i = 0; i < n; ++i) {
    double sum = (*x)[i];
    for (std::size_t k = 0; k < i; ++k) sum -= l[i * n + k] * (*x)[k];
    (*x)[i] = sum / l[i * n + i];
  }
}

// Solves L^T x = b in place.
void Backward(const std::vector<double>& l, std::vector<double>* x) {
  const std::size_t n = x->size();
  for (std::size_t i = n; i-- > 0;) {
    double sum = (*x)[i];
    for (std::size_t k = i + 1; k < n; ++k) sum -= l[k * n + i] * (*x)[k];
    (*x)[i] = sum / l[i * n + i];
  }
}

// A regressor in d-space (sparse for steps) with its GLS normalisation 1 / sqrt(h^T C^-1 h).
struct Regressor {
  std::vector<std::pair<std::size_t, double>> h;
  double inv_norm = 0.0;  // 1 / sqrt(h^T C^{-1} h)
  double where_s = 0.0;   // the step's time or the settling's time constant
  double Dot(const std::vector<double>& w) const {
    double s = 0.0;
    for (const auto& [i, v] : h) s += v * w[i];
    return s;
  }
};

struct Family {
  std::vector<Regressor> regressors;
  double best_t = 0.0, best_size = 0.0, best_sd = kNaN, best_where = kNaN;
  // The largest (h . w)^2 / (h^T C^-1 h) over the family, w = C^{-1} d.
  double Max(const std::vector<double>& w) const {
    double best = 0.0;
    for (const Regressor& r : regressors) {
      const double t = r.Dot(w) * r.inv_norm;
      best = std::max(best, t * t);
    }
    return best;
  }
  // The best of statistics computed elsewhere, one per regressor (profiled_step.h).
  void Observe(const std::vector<ProfiledStep>& fits) {
    for (std::size_t i = 0; i < fits.size() && i < regressors.size(); ++i) {
      if (fits[i].t > best_t) {
        best_t = fits[i].t;
        best_size = fits[i].size;
        best_sd = fits[i].sd;
        best_where = regressors[i].where_s;
      }
    }
  }
  void Observe(const std::vector<double>& w) {
    for (const Regressor& r : regressors) {
      const double g = r.Dot(w);
      const double t = g * r.inv_norm * g * r.inv_norm;
      if (t > best_t) {
        best_t = t;
        best_size = g * r.inv_norm * r.inv_norm;  // GLS size: h.w / (h^T C^-1 h)
        best_sd = r.inv_norm;
        best_where = r.where_s;
      }
    }
  }
};

// A unit step at the edge after block i (d_i = 1) and at the middle of block i + 1
// (d_i = d_{i+1} = 1/2), located at the step's time.
Family StepFamily(std::size_t dim, double block_s) {
  Family f;
  for (std::size_t i = 0; i < dim; ++i) {
    f.regressors.push_back({{{i, 1.0}}, 0.0, static_cast<double>(i + 1) * block_s});
    if (i + 1 < dim) f.regressors.push_back({{{i, 0.5}, {i + 1, 0.5}}, 0.0, (static_cast<double>(i) + 1.5) * block_s});
  }
  return f;
}

// A unit settling e^{-t / tw} from the start, tw = 2 m tau0 .. 4 N tau0 by sqrt 2: block b's mean
// is e^{-b m tau0 / tw} (1 - rho^m) / (m (1 - rho)), rho = e^{-tau0 / tw} (the generator's sample
// times, sim/exponential_drift.h); located by tw.
Family SettlingFamily(std::size_t dim, std::int64_t m, double tau0, std::int64_t n) {
  Family f;
  const double block_s = static_cast<double>(m) * tau0, record_s = static_cast<double>(n) * tau0;
  for (double tw = 2.0 * block_s; tw <= 4.0 * record_s * (1.0 + 1e-9); tw *= std::sqrt(2.0)) {
    const double within = std::expm1(-block_s / tw) / (static_cast<double>(m) * std::expm1(-tau0 / tw));
    Regressor reg;
    reg.where_s = tw;
    for (std::size_t i = 0; i < dim; ++i) {
      const double a = std::exp(-static_cast<double>(i) * block_s / tw);
      const double b = std::exp(-static_cast<double>(i + 1) * block_s / tw);
      reg.h.push_back({i, (b - a) * within});
    }
    f.regressors.push_back(std::move(reg));
  }
  return f;
}

// Each family's maximum under the model: w = L^{-T} e, e ~ N(0, I), fixed draws per block count.
void NullMaxima(const std::vector<double>& l, int blocks, const Family& steps, const Family& settlings,
                std::vector<double>* null_step, std::vector<double>* null_settle) {
  sim::Engine engine = sim::MakeEngine(kNullSeed, static_cast<std::uint64_t>(blocks), 0);
  boost::random::normal_distribution<double> normal(0.0, 1.0);
  std::vector<double> e(static_cast<std::size_t>(blocks - 1));
  null_step->resize(kBlockMeanNullDraws);
  null_settle->resize(kBlockMeanNullDraws);
  for (int draw = 0; draw < kBlockMeanNullDraws; ++draw) {
    for (double& x : e) x = normal(engine);
    Backward(l, &e);
    (*null_step)[draw] = steps.Max(e);
    (*null_settle)[draw] = settlings.Max(e);
  }
}

void Normalise(const std::vector<double>& l, std::size_t n, Family* f) {
  for (Regressor& r : f->regressors) {
    std::vector<double> q(n, 0.0);
    for (const auto& [i, v] : r.h) q[i] = v;
    Forward(l, &q);
    double norm2 = 0.0;
    for (double x : q) norm2 += x * x;
    r.inv_norm = norm2 > 0.0 ? 1.0 / std::sqrt(norm2) : 0.0;
  }
}

// p = (1 + exceedances) / (draws + 1) from the draws; beyond the 20th largest draw T0 the tail is
// extrapolated as p(T0) P(chi2_1 > T) / P(chi2_1 > T0) (the tail shape of a maximum of chi2_1
// statistics; docs/theory.md §6.7).
void AddPoint(const Family& f, std::vector<double> null, double x_s, ViewResiduals* v) {
  constexpr std::size_t kTailDraws = 20;
  std::sort(null.begin(), null.end(), std::greater<>());
  const auto draws = static_cast<double>(null.size());
  const double t0 = null[kTailDraws - 1];
  double p = 0.0;
  if (f.best_t <= t0) {
    const auto exceed = std::upper_bound(null.begin(), null.end(), f.best_t, std::greater<>()) - null.begin();
    p = (1.0 + static_cast<double>(exceed)) / (draws + 1.0);
  } else {
    p = static_cast<double>(kTailDraws) / (draws + 1.0) * std::erfc(std::sqrt(0.5 * f.best_t)) /
        std::erfc(std::sqrt(0.5 * t0));
  }
  v->x.push_back(x_s);
  v->observed.push_back(f.best_size);
  v->expected.push_back(f.best_sd);
  v->z.push_back(std::copysign(ZFromTwoSidedP(p), f.best_size));
  v->time_s.push_back(f.best_where);
}

void AddNaN(double x_s, ViewResiduals* v) {
  v->x.push_back(x_s);
  v->observed.push_back(kNaN);
  v->expected.push_back(kNaN);
  v->z.push_back(kNaN);
  v->time_s.push_back(kNaN);
}

}  // namespace

bool LocatedStep(const std::vector<ViewResiduals>& views, double threshold, double* time_s, double* block_s) {
  double best = threshold;
  bool found = false;
  for (const ViewResiduals& v : views) {
    if (v.view != View::kChangePoint) continue;
    for (std::size_t i = 0; i < v.z.size() && i < v.time_s.size(); ++i) {
      if (std::abs(v.z[i]) > best) {
        best = std::abs(v.z[i]);
        *time_s = v.time_s[i];
        *block_s = v.x[i];
        found = true;
      }
    }
  }
  return found;
}

std::vector<double> BlockMeans(std::span<const double> x, int blocks) {
  const std::size_t m = x.size() / static_cast<std::size_t>(blocks);
  std::vector<double> means(static_cast<std::size_t>(blocks), 0.0);
  for (std::size_t b = 0; b < means.size(); ++b) {
    double sum = 0.0;
    for (std::size_t k = b * m; k < (b + 1) * m; ++k) sum += x[k];
    means[b] = sum / static_cast<double>(m);
  }
  return means;
}

std::vector<double> DeterministicPath(const sim::SensorModel& model, std::int64_t n) {
  sim::SensorModel events;
  events.sample_clock = model.sample_clock;
  for (const sim::NoiseTerm& t : model.terms) {
    if (IsEvent(t)) events.terms.push_back(t);
  }
  return events.terms.empty() ? std::vector<double>() : events.Generate(0, 0, n);
}

std::vector<int> BlockMeanCounts(std::int64_t n) {
  std::vector<int> out;
  for (int b : {64, 32, 16}) {  // ascending block length, as every view's x
    if (n / b >= 16) out.push_back(b);
  }
  return out;
}

std::vector<double> BlockDifferenceCovariance(const sim::SensorModel& model, std::int64_t m, int blocks) {
  const std::vector<double> r = RandomPartAutocovariance(model, blocks * m + 1);
  const double block_s = static_cast<double>(m) * model.sample_clock.period_s();
  return CovarianceFromAutocovariance(r, m, blocks, RampSquared(model) * block_s * block_s);
}

std::vector<double> BlockMeanDeviationSd(const sim::SensorModel& model, std::int64_t m, int blocks) {
  const std::vector<double> r = RandomPartAutocovariance(model, blocks * m + 1);
  std::vector<long double> d = StructureFunction(r, m, blocks);
  // A ramp of unknown sign, a random slope R: D(k) += R^2 (k m tau0)^2.
  const long double block_s = static_cast<long double>(m) * model.sample_clock.period_s();
  const long double r2 = RampSquared(model);
  for (int k = 1; k < blocks; ++k) d[k] += r2 * (k * block_s) * (k * block_s);
  // Var(u_b - mean_j u_j) = (1/B) sum_j D(|b - j|) - (1/(2 B^2)) sum_i sum_j D(|i - j|).
  const auto b_count = static_cast<long double>(blocks);
  long double all = 0.0L;
  for (int k = 1; k < blocks; ++k) all += 2.0L * (b_count - k) * d[k];
  std::vector<double> sd(static_cast<std::size_t>(blocks));
  for (int b = 0; b < blocks; ++b) {
    long double row = 0.0L;
    for (int j = 0; j < blocks; ++j) row += d[static_cast<std::size_t>(std::abs(b - j))];
    const long double var = row / b_count - all / (2.0L * b_count * b_count);
    sd[b] = var > 0.0L ? static_cast<double>(std::sqrt(var)) : 0.0;
  }
  return sd;
}

void BlockMeanResiduals(std::span<const double> rate, double tau0, std::span<const int> block_counts,
                        const sim::SensorModel& model, double rate_random_walk_bound, ViewResiduals* change_point,
                        ViewResiduals* trend) {
  *change_point = ViewResiduals{};
  *trend = ViewResiduals{};
  change_point->view = View::kChangePoint;
  trend->view = View::kTrend;
  if (block_counts.empty()) return;
  const auto n = static_cast<std::int64_t>(rate.size());
  // The record less the model's deterministic path (its steps and warm-up drifts, placed in time).
  const std::vector<double> path = DeterministicPath(model, n);
  std::int64_t longest = 0;
  for (int b : block_counts) longest = std::max(longest, b * (n / b));
  const std::vector<double> r = RandomPartAutocovariance(model, longest + 1);
  const double r2 = RampSquared(model);
  // A unit rate random walk's generalised autocovariance, -|j| tau0 / 2 (sim/random_walk_rate.h).
  std::vector<double> unit_walk;
  const bool profile_k = rate_random_walk_bound > 0.0;
  if (profile_k) {
    unit_walk.resize(static_cast<std::size_t>(longest + 1));
    for (std::size_t j = 0; j < unit_walk.size(); ++j) unit_walk[j] = -0.5 * static_cast<double>(j) * tau0;
  }
  const double k2 = RandomWalkSquared(model);
  // K's range: up to the most the record allows, not only the fitted value (a fit that drops K
  // would otherwise judge a random walk's wander as steps).
  const double k2_max = std::max(k2, rate_random_walk_bound * rate_random_walk_bound);
  for (int blocks : block_counts) {
    const std::int64_t m = n / blocks;
    const double block_s = static_cast<double>(m) * tau0;
    const std::vector<double> c = CovarianceFromAutocovariance(r, m, blocks, r2 * block_s * block_s);
    const std::size_t dim = c.size();
    std::vector<double> l;
    if (!Cholesky(c, &l)) {
      AddNaN(block_s, change_point);
      AddNaN(block_s, trend);
      continue;
    }
    std::vector<double> u(static_cast<std::size_t>(blocks), 0.0);
    for (int b = 0; b < blocks; ++b) {
      long double sum = 0.0L;
      for (std::int64_t k = b * m; k < (b + 1) * m; ++k) sum += rate[k] - (path.empty() ? 0.0 : path[k]);
      u[b] = static_cast<double>(sum / static_cast<long double>(m));
    }
    std::vector<double> d(dim);
    for (std::size_t i = 0; i < dim; ++i) d[i] = u[i + 1] - u[i];
    std::vector<double> w = d;
    Forward(l, &w);
    Backward(l, &w);  // w = C^{-1} d
    Family steps = StepFamily(dim, block_s), settlings = SettlingFamily(dim, m, tau0, n);
    Normalise(l, dim, &steps);
    Normalise(l, dim, &settlings);
    std::vector<ProfiledStep> profiled;
    std::vector<double> null_step, null_settle;
    if (profile_k && k2_max > 0.0) {
      const std::vector<double> unit = CovarianceFromAutocovariance(unit_walk, m, blocks, 0.0);
      std::vector<double> c0(dim);
      for (std::size_t i = 0; i < dim; ++i) c0[i] = c[i] - k2 * unit[i];
      std::vector<SparseRegressor> h;
      for (const Regressor& reg : steps.regressors) h.push_back(reg.h);
      if (!ProfileSteps(c0, unit, k2_max, d, h, kProfiledNullDraws, static_cast<std::uint64_t>(blocks), &profiled,
                        &null_step)) {
        profiled.clear();
      }
    }
    if (profiled.empty()) {
      steps.Observe(w);
    } else {
      steps.Observe(profiled);
    }
    settlings.Observe(w);
    std::vector<double> held_null_step;
    NullMaxima(l, blocks, steps, settlings, &held_null_step, &null_settle);
    if (profiled.empty()) null_step = std::move(held_null_step);
    AddPoint(steps, std::move(null_step), block_s, change_point);
    AddPoint(settlings, std::move(null_settle), block_s, trend);
  }
}

}  // namespace allanlab::experiments
