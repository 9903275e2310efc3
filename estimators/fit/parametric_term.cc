#include "estimators/fit/parametric_term.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <Eigen/Dense>

#include "estimators/fit/parametric_fit.h"
#include "sim/band_limited_avar.h"
#include "sim/units.h"

namespace allanlab::estimators {
namespace {

double MaxAvar(const AvarCurve& c) { return *std::max_element(c.avar.begin(), c.avar.end()); }
double MinAvar(const AvarCurve& c) { return *std::min_element(c.avar.begin(), c.avar.end()); }
double Edf(const AvarCurve& c, std::size_t k) {
  return c.edf.empty() ? std::max(1.0, static_cast<double>(c.num_samples / c.m[k] - 1)) : c.edf[k];
}

// Best amplitude^2 of a unit shape against the residual, by the weighted projection with
// weights nu/(2 a^2); returns the weighted-SSE reduction (0 if the amplitude would be < 0).
double Project(const AvarCurve& c, std::span<const double> residual, const std::vector<double>& shape,
               double* amplitude2) {
  double sr = 0.0, ss = 0.0;
  for (std::size_t k = 0; k < c.size(); ++k) {
    const double w = 0.5 * Edf(c, k) / (c.avar[k] * c.avar[k]);
    sr += w * shape[k] * residual[k];
    ss += w * shape[k] * shape[k];
  }
  if (!(ss > 0.0) || sr <= 0.0) return 0.0;
  *amplitude2 = sr / ss;
  return sr * sr / ss;
}

// A log grid from lo to hi with `per_decade` points.
std::vector<double> LogGrid(double lo, double hi, double per_decade) {
  std::vector<double> g;
  for (double x = lo; x <= hi * (1.0 + 1e-12); x *= std::pow(10.0, 1.0 / per_decade)) g.push_back(x);
  return g;
}

// Smallest weighted SSE (weights nu/(2 a^2)) of sum_i x_i columns[i] against the curve over
// x >= 0: every subset of columns solved unconstrained, infeasible ones skipped (a handful of
// columns, so 2^n small solves).
double BestNonNegativeFit(const AvarCurve& c, const std::vector<std::vector<double>>& columns) {
  const auto n = static_cast<Eigen::Index>(c.size());
  const auto p = static_cast<int>(columns.size());
  Eigen::VectorXd y(n);
  Eigen::MatrixXd a(n, p);
  for (Eigen::Index k = 0; k < n; ++k) {
    const auto kk = static_cast<std::size_t>(k);
    const double sw = std::sqrt(0.5 * Edf(c, kk)) / c.avar[kk];
    y(k) = sw * c.avar[kk];
    for (int i = 0; i < p; ++i) a(k, i) = sw * columns[static_cast<std::size_t>(i)][kk];
  }
  double best = y.squaredNorm();
  for (int mask = 1; mask < (1 << p); ++mask) {
    std::vector<Eigen::Index> cols;
    for (int i = 0; i < p; ++i) {
      if (mask & (1 << i)) cols.push_back(i);
    }
    Eigen::MatrixXd sub(n, static_cast<Eigen::Index>(cols.size()));
    for (std::size_t j = 0; j < cols.size(); ++j) sub.col(static_cast<Eigen::Index>(j)) = a.col(cols[j]);
    const Eigen::VectorXd x = sub.colPivHouseholderQr().solve(y);
    if ((x.array() < 0.0).any() || !x.allFinite()) continue;
    best = std::min(best, (y - sub * x).squaredNorm());
  }
  return best;
}

// A term with one amplitude and one scale parameter whose continuous AVAR shape (unit amplitude)
// seeds the grid search of its initial guess.
class AmplitudeScaleTerm : public ParametricTerm {
 public:
  const std::vector<ParameterSpec>& parameters() const override { return specs_; }
  bool InitialGuess(const AvarCurve& curve, std::span<const double> residual,
                    const sim::SensorModel&, std::vector<double>* params, std::string* why) const override {
    std::vector<double> lower, upper;
    Bounds(curve, &lower, &upper);
    double best = 0.0, best_scale = 0.0, best_amp2 = 0.0;
    for (double scale : LogGrid(lower[1], upper[1], 20.0)) {
      std::vector<double> shape;
      for (double tau : curve.tau_s) shape.push_back(UnitAsymptote(scale, tau));
      double amp2 = 0.0;
      const double gain = Project(curve, residual, shape, &amp2);
      if (gain > best) {
        best = gain;
        best_scale = scale;
        best_amp2 = amp2;
      }
    }
    if (best <= 0.0) {
      if (why) *why = "no positive residual this term's shape could explain";
      return false;
    }
    const double amp = std::clamp(std::sqrt(best_amp2), lower[0] * 1.01, upper[0] * 0.99);
    *params = {amp, best_scale};
    return true;
  }
  void Bounds(const AvarCurve& curve, std::vector<double>* lower, std::vector<double>* upper) const override {
    const double lo_amp = std::sqrt(MinAvar(curve)) * 1e-4, hi_amp = std::sqrt(MaxAvar(curve)) * 30.0;
    double lo_scale = 0.0, hi_scale = 0.0;
    ScaleBounds(curve, &lo_scale, &hi_scale);
    *lower = {lo_amp, lo_scale};
    *upper = {hi_amp, hi_scale};
  }

 protected:
  virtual double UnitAsymptote(double scale, double tau) const = 0;
  virtual void ScaleBounds(const AvarCurve& curve, double* lo, double* hi) const = 0;
  std::vector<ParameterSpec> specs_;
};

ParameterSpec RateAmplitude(const char* name) {
  return {name, "rad/s", "deg/h", units::DegPerHour(1.0), 0.0,
          std::numeric_limits<double>::infinity(), true};
}

class GaussMarkovTerm final : public AmplitudeScaleTerm {
 public:
  GaussMarkovTerm() {
    specs_ = {RateAmplitude("sigma"),
              {"Tc", "s", "s", 1.0, 0.0, std::numeric_limits<double>::infinity(), true}};
  }
  std::string_view id() const override { return sim::GaussMarkov::kId; }
  std::string_view short_name() const override { return "GM"; }
  void ApplyTo(std::span<const double> p, sim::SensorModel* model) const override {
    model->terms.push_back(sim::GaussMarkov{p[0], p[1]});
  }

 private:
  double UnitAsymptote(double tc, double tau) const override {
    return sim::GaussMarkov{1.0, tc}.AsymptoticAvar(tau);
  }
  // The AVAR peak (1.89 Tc) within a decade of the curve's taus.
  void ScaleBounds(const AvarCurve& c, double* lo, double* hi) const override {
    *lo = c.tau_s.front() / 10.0;
    *hi = c.tau_s.back() * 10.0;
  }
};

// The telegraph's AVAR is the Gauss-Markov one with sigma = a, Tc = T/2 (sim/random_telegraph.h):
// same shape, its own parameters, so a fit reports the telegraph's amplitude and dwell directly.
class RandomTelegraphTerm final : public AmplitudeScaleTerm {
 public:
  RandomTelegraphTerm() {
    specs_ = {RateAmplitude("a"),
              {"dwell", "s", "s", 1.0, 0.0, std::numeric_limits<double>::infinity(), true}};
  }
  std::string_view id() const override { return sim::RandomTelegraph::kId; }
  std::string_view short_name() const override { return "RTS"; }
  void ApplyTo(std::span<const double> p, sim::SensorModel* model) const override {
    model->terms.push_back(sim::RandomTelegraph{p[0], p[1]});
  }

 private:
  double UnitAsymptote(double dwell, double tau) const override {
    return sim::RandomTelegraph{1.0, dwell}.AsymptoticAvar(tau);
  }
  // As the Gauss-Markov term with Tc = dwell / 2.
  void ScaleBounds(const AvarCurve& c, double* lo, double* hi) const override {
    *lo = c.tau_s.front() / 5.0;
    *hi = c.tau_s.back() * 20.0;
  }
};

class HarmonicTerm final : public AmplitudeScaleTerm {
 public:
  HarmonicTerm() {
    specs_ = {RateAmplitude("Omega0"),
              {"f0", "Hz", "Hz", 1.0, 0.0, std::numeric_limits<double>::infinity(), true}};
  }
  std::string_view id() const override { return sim::Harmonic::kId; }
  std::string_view short_name() const override { return "H"; }
  void ApplyTo(std::span<const double> p, sim::SensorModel* model) const override {
    model->terms.push_back(sim::Harmonic{p[0], p[1], std::nullopt});
  }

 private:
  double UnitAsymptote(double f0, double tau) const override {
    return sim::Harmonic{1.0, f0, std::nullopt}.AsymptoticAvar(tau);
  }
  // From a tenth of a cycle over the longest tau to just below the output Nyquist frequency.
  void ScaleBounds(const AvarCurve& c, double* lo, double* hi) const override {
    *lo = 0.1 / c.tau_s.back();
    *hi = 0.499 / c.sample_clock.period_s();
  }
};

class BandLimitTerm final : public ParametricTerm {
 public:
  BandLimitTerm(sim::LowPassKind kind, sim::OutputSampling sampling, int oversampling)
      : kind_(kind), sampling_(sampling), oversampling_(oversampling) {
    specs_ = {{"fc", "Hz", "Hz", 1.0, 0.0, std::numeric_limits<double>::infinity(), true}};
  }
  std::string_view id() const override { return "bandwidth"; }
  // BW / BW2 for the two filters of `fit --terms` (whatever the sampling and L, as before the
  // family); the other filters by their family name.
  std::string_view short_name() const override {
    if (kind_ == sim::LowPassKind::kFirstOrder) return "BW";
    if (kind_ == sim::LowPassKind::kButterworth2) return "BW2";
    const sim::BandLimitFamily* f = sim::FamilyOf(sim::BandLimit{kind_, 1.0, oversampling_, sampling_});
    return f != nullptr ? f->name : "BW";
  }
  const std::vector<ParameterSpec>& parameters() const override { return specs_; }
  bool modifies_other_terms() const override { return true; }
  // From a thousandth of the output rate (or a tenth of the inverse longest tau, if higher) to
  // 0.45 of the internal rate. The floor keeps the chain's impulse response (about
  // 41 L fs / (2 pi fc) internal samples to its 1e-18 tail) under ~5e4 L samples: with
  // 0.1 / tau_max alone, a long record (rlg) let the line search try fc ~ 1e-4 Hz, whose chain
  // runs to 2^26 samples, and the fit never finished.
  void Bounds(const AvarCurve& c, std::vector<double>* lower, std::vector<double>* upper) const override {
    *lower = {std::max(0.1 / c.tau_s.back(), 1e-3 / c.sample_clock.period_s())};
    *upper = {BandLimitMaxCutoffHz(kind_, oversampling_, c.sample_clock.period_s())};
  }
  void ApplyTo(std::span<const double> p, sim::SensorModel* model) const override {
    model->band_limit = sim::BandLimit{kind_, p[0], oversampling_, sampling_};
  }
  // ScreenBandLimit's cutoff. Rescaling each term matters: a baseline fitted without the
  // band-limit has bent its terms to mimic it (N low, B high).
  bool InitialGuess(const AvarCurve& curve, std::span<const double>, const sim::SensorModel& without,
                    std::vector<double>* params, std::string* why) const override {
    double fc = 0.0, ratio = 1.0;
    if (!ScreenBandLimit(kind_, sampling_, oversampling_, curve, without, &fc, &ratio)) {
      if (why) *why = "no cutoff improves the fit of the short taus";
      return false;
    }
    *params = {fc};
    return true;
  }

 private:
  sim::LowPassKind kind_;
  sim::OutputSampling sampling_;
  int oversampling_;
  std::vector<ParameterSpec> specs_;
};

}  // namespace

double BandLimitMaxCutoffHz(sim::LowPassKind kind, int oversampling, double output_period_s) {
  // A box kind must stay at least one internal sample long (its fc <= 0.319 L fs for CIC2).
  return (sim::IsFirLowPass(kind) ? 0.3 : 0.45) * oversampling / output_period_s;
}

bool ScreenBandLimit(sim::LowPassKind kind, sim::OutputSampling sampling, int oversampling,
                     const AvarCurve& curve, const sim::SensorModel& without, double* cutoff_hz,
                     double* sse_ratio) {
  const BandLimitTerm term(kind, sampling, oversampling);
  std::vector<double> lower, upper;
  term.Bounds(curve, &lower, &upper);
  // Each baseline term's own AVAR once; each cutoff adds the band-limit's change.
  std::vector<std::vector<double>> own;
  for (const sim::NoiseTerm& t : without.terms) {
    sim::SensorModel one = without;
    one.terms = {t};
    own.push_back(ModelAvarOnCurve(one, curve));
  }
  const double baseline = BestNonNegativeFit(curve, own);
  double best = baseline, best_fc = 0.0;
  // 12 cutoffs a decade: a box's correlation with the next output changes by ~0.1 between grid
  // points near a box of one output period (6 a decade left a 1.2-period box between 0.95 and 1.4).
  // A filter at the output rate also at its highest cutoff: with it there (a 45 Hz digital filter
  // at 100 Hz) it bends the shortest taus less than the grid's last point (38 Hz) would, so
  // without it such a filter screened as no improvement and was never fitted. (A faster chain's
  // highest cutoff is far above what the curve can see.)
  std::vector<double> grid = LogGrid(std::max(lower[0], 0.01 / curve.sample_clock.period_s()), upper[0], 12.0);
  if (oversampling == 1 && (grid.empty() || grid.back() < upper[0] * (1.0 - 1e-9))) grid.push_back(upper[0]);
  for (double fc : grid) {
    sim::SensorModel model = without;
    const double p[] = {fc};
    term.ApplyTo(p, &model);
    std::string invalid;
    if (!model.band_limit.IsValid(model.sample_clock.rate_hz(), &invalid)) continue;  // a box under one sample
    const sim::BandLimitChain chain(model.band_limit, model.sample_clock.rate_hz());
    std::vector<std::vector<double>> columns = own;
    std::vector<double> change;
    for (std::size_t i = 0; i < without.terms.size(); ++i) {
      if (sim::BandLimitAvarChange(without.terms[i], chain, curve.sample_clock.period_s(), curve.m, &change)) {
        for (std::size_t k = 0; k < change.size(); ++k) columns[i][k] += change[k];
      } else {
        sim::SensorModel one = model;
        one.terms = {without.terms[i]};
        columns[i] = ModelAvarOnCurve(one, curve);
      }
    }
    const double s = BestNonNegativeFit(curve, columns);
    if (s < best) {
      best = s;
      best_fc = fc;
    }
  }
  if (best_fc == 0.0) return false;
  *cutoff_hz = best_fc;
  *sse_ratio = baseline > 0.0 ? best / baseline : 0.0;
  return true;
}

void ParametricTerm::Bounds(const AvarCurve&, std::vector<double>* lower, std::vector<double>* upper) const {
  lower->clear();
  upper->clear();
  for (const ParameterSpec& s : parameters()) {
    lower->push_back(s.lower_si);
    upper->push_back(s.upper_si);
  }
}

std::unique_ptr<ParametricTerm> MakeGaussMarkovTerm() { return std::make_unique<GaussMarkovTerm>(); }
std::unique_ptr<ParametricTerm> MakeRandomTelegraphTerm() { return std::make_unique<RandomTelegraphTerm>(); }
std::unique_ptr<ParametricTerm> MakeHarmonicTerm() { return std::make_unique<HarmonicTerm>(); }
std::unique_ptr<ParametricTerm> MakeBandLimitTerm(sim::LowPassKind kind, sim::OutputSampling sampling,
                                                  int oversampling) {
  return std::make_unique<BandLimitTerm>(kind, sampling, oversampling);
}

std::unique_ptr<ParametricTerm> MakeParametricTerm(std::string_view name) {
  if (name == "GM" || name == "gauss_markov") return MakeGaussMarkovTerm();
  if (name == "RTS" || name == "random_telegraph") return MakeRandomTelegraphTerm();
  if (name == "H" || name == "harmonic") return MakeHarmonicTerm();
  if (name == "RES" || name == "resonance") return MakeResonanceTerm();
  if (name == "BW" || name == "bandwidth") return MakeBandLimitTerm(sim::LowPassKind::kFirstOrder);
  if (name == "BW2") return MakeBandLimitTerm(sim::LowPassKind::kButterworth2);
  return nullptr;
}

}  // namespace allanlab::estimators
