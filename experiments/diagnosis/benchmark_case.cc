#include "experiments/diagnosis/benchmark_case.h"

#include <algorithm>
#include <cmath>

#include "estimators/fit/fit_avar_model.h"
#include "estimators/fit/noise_coefficient.h"
#include "estimators/tau_grid.h"
#include "experiments/diagnosis/candidate_estimate.h"
#include "experiments/diagnosis/envelope.h"
#include "sim/seeding.h"
#include "sim/sensor_spec.h"

namespace allanlab::experiments {
namespace {

using estimators::Coefficient;

// What the strength of every trial parameter value shares: the grids and the baseline's EDFs.
struct StrengthGrid {
  std::vector<std::int64_t> ms;
  std::vector<double> tau_s, edf;
  std::int64_t n = 0;
  // Halves view (non-stationary effects only): octave m <= N/16 on records of N/2 samples.
  std::vector<std::int64_t> halves_ms;
  std::vector<double> halves_edf;
};

StrengthGrid MakeGrid(const sim::SensorModel& base, std::int64_t n, bool halves) {
  StrengthGrid g;
  g.n = n;
  estimators::TauGridOptions grid;
  grid.kind = estimators::TauGridKind::kLogDense;
  grid.points_per_decade = 10;
  const double tau0 = base.sample_clock.period_s();
  g.ms = estimators::CandidateAveragingFactors(grid, tau0, n / 2);
  for (std::int64_t m : g.ms) g.tau_s.push_back(static_cast<double>(m) * tau0);
  g.edf = ExactOavar(base, g.ms, n).edf;
  if (halves) {
    for (std::int64_t m = 1; m <= n / 16; m *= 2) g.halves_ms.push_back(m);
    g.halves_edf = ExactOavar(base, g.halves_ms, n / 2).edf;
  }
  return g;
}

bool IsNonStationary(const std::optional<EffectInstance>& e) {
  return e && (e->effect == Effect::kBiasStep || e->effect == Effect::kExponentialDrift);
}

bool Build(const sim::SensorModel& base, const std::optional<EffectInstance>& effect,
           sim::SensorModel* full, std::string* why) {
  *full = base;
  if (effect && !AddEffect(*effect, full, why)) return false;
  return full->IsValid(why);
}

// Expected excess kurtosis of the first differences of the samples from the effects that make
// them non-Gaussian, as independent additive errors of known cumulants (spikes with small p;
// quantization errors uniform over an LSB: Sheppard's regime, LSB below the noise).
double ExcessKurtosis(const std::optional<EffectInstance>& e, double tau0, double variance_of_difference) {
  if (!e) return 0.0;
  const double v2 = variance_of_difference * variance_of_difference;
  switch (e->effect) {
    case Effect::kOutliers: {
      // A spike +-a with probability p enters two differences: kappa4 = 2 p a^4 (1 - 3 p).
      const double p = e->params.at("rate_hz") * tau0, a = e->params.at("size_rad_per_s");
      return 2.0 * p * std::pow(a, 4) * (1.0 - 3.0 * p) / v2;
    }
    case Effect::kRateQuantization: {
      // Error uniform, kappa4 = -1.2 (q^2/12)^2, entering two differences.
      const double q2 = std::pow(e->params.at("lsb_rad_per_s"), 2) / 12.0;
      return -2.4 * q2 * q2 / v2;
    }
    case Effect::kAngleQuantization: {
      // Angle error e_k uniform; the rate carries (e_k - e_{k-1}) / tau0, its differences
      // (e_{k+1} - 2 e_k + e_{k-1}) / tau0, so kappa4 = (1 + 16 + 1) (-1.2) (q^2/12)^2 / tau0^4
      // (q2 below is the rate-scale variance q^2 / (12 tau0^2)).
      const double q2 = std::pow(e->params.at("lsb_rad") / tau0, 2) / 12.0;
      return -1.2 * 18.0 * q2 * q2 / v2;
    }
    default:
      return 0.0;
  }
}

// Strength of base + effect on the grid; fills the per-tau fields of *c and c->model. False when
// the model or the fit fails.
bool Measure(const StrengthGrid& g, const sim::SensorModel& base, const std::optional<EffectInstance>& effect,
             BenchmarkCase* c, std::string* why) {
  sim::SensorModel full;
  if (!Build(base, effect, &full, why)) return false;
  const sim::RecordShape shape{g.n, sim::AvarEstimatorKind::kOverlapping};
  const double tau0 = full.sample_clock.period_s();
  estimators::AvarCurve curve;
  curve.sample_clock = full.sample_clock;
  curve.num_samples = g.n;
  curve.m = g.ms;
  curve.tau_s = g.tau_s;
  curve.avar = full.ExpectedAvar(g.ms, shape);
  curve.edf = g.edf;
  for (double& a : curve.avar) a = std::max(a, 1e-300);
  estimators::FitOptions fo;
  fo.method = estimators::FitMethod::kWls;
  fo.select_terms = false;
  estimators::FitSummary fit;
  if (!estimators::FitAvarModel(fo, curve, &fit)) {
    *why = "strength: baseline fit to the expected curve failed: " + fit.message;
    return false;
  }
  sim::SensorModel fitted;
  fitted.sample_clock = full.sample_clock;
  for (Coefficient k : estimators::kAllCoefficients) {
    const auto& e = fit.at(k);
    if (e.fitted && e.value_si > 0.0) fitted.terms.push_back(estimators::TermFor(k, e.value_si));
  }
  const std::vector<double> e_fit = fitted.ExpectedAvar(g.ms, shape);
  c->tau_s = g.tau_s;
  c->gap_z.assign(g.ms.size(), 0.0);
  c->strength_z = c->oavar_z = c->relative_peak = c->peak_tau_s = 0.0;
  for (std::size_t i = 0; i < g.ms.size(); ++i) {
    if (!(e_fit[i] > 0.0) || !(g.edf[i] > 0.0)) continue;
    const double ratio = curve.avar[i] / e_fit[i];
    c->gap_z[i] = std::abs(std::log(ratio)) * std::sqrt(g.edf[i] / 2.0);
    c->relative_peak = std::max(c->relative_peak, std::abs(ratio - 1.0));
    if (c->gap_z[i] > c->oavar_z) {
      c->oavar_z = c->gap_z[i];
      c->peak_tau_s = g.tau_s[i];
    }
  }
  c->kurtosis_z = std::abs(ExcessKurtosis(effect, tau0, 2.0 * full.ExpectedAvar(1, shape))) /
                  std::sqrt(24.0 / static_cast<double>(g.n));
  c->halves_z = c->halves_peak_tau_s = 0.0;
  if (IsNonStationary(effect) && !g.halves_ms.empty()) {
    // ln(OAVAR_first / OAVAR_second) has variance 2/nu + 2/nu under the model.
    const sim::RecordShape half{g.n / 2, sim::AvarEstimatorKind::kOverlapping};
    sim::SensorModel second;
    if (!Build(base, ShiftEffect(*effect, static_cast<double>(g.n / 2) * tau0), &second, why)) return false;
    const auto f1 = full.ExpectedAvar(g.halves_ms, half);
    const auto f2 = second.ExpectedAvar(g.halves_ms, half);
    for (std::size_t i = 0; i < g.halves_ms.size(); ++i) {
      if (!(f1[i] > 0.0) || !(f2[i] > 0.0) || !(g.halves_edf[i] > 0.0)) continue;
      const double z = std::abs(std::log(f1[i] / f2[i])) * std::sqrt(g.halves_edf[i] / 4.0);
      if (z > c->halves_z) {
        c->halves_z = z;
        c->halves_peak_tau_s = static_cast<double>(g.halves_ms[i]) * tau0;
      }
    }
  }
  c->strength_z = std::max({c->oavar_z, c->kurtosis_z, c->halves_z});
  c->model = std::move(full);
  return true;
}

// Uniform in [0, 1) from 53 random bits: the same on every platform and standard library.
double Uniform(sim::Engine& engine) { return static_cast<double>(engine() >> 11) * 0x1.0p-53; }
double LogUniform(double u, double lo, double hi) { return lo * std::pow(hi / lo, u); }

// The effect with its strength parameter (the one solved for) and the range it may take.
struct Scaled {
  EffectInstance effect;
  std::string parameter;
  double lo = 0.0, hi = 0.0;
  bool increasing = true;  // strength grows with the parameter (bandwidth: falls with fc)
};

Scaled Shape(Effect e, const double u[2], SampleClock clock, double n, double s0) {
  const double fs = clock.rate_hz(), tau0 = clock.period_s(), T = n * tau0;
  Scaled s;
  s.effect.effect = e;
  auto& p = s.effect.params;
  switch (e) {
    case Effect::kBandwidth: {
      // Any filter family (analog or digital, first or second order, box or CIC), its cutoff
      // below the output Nyquist frequency (above it a fit is refused: physical_bounds.h).
      const auto& families = sim::BandLimitFamilies();
      const std::size_t f = std::min(families.size() - 1, static_cast<std::size_t>(u[1] * families.size()));
      p["family"] = static_cast<double>(f);
      p["order"] = families[f].order;
      s.parameter = "cutoff_hz";
      s.lo = fs / 200.0;
      s.hi = 0.45 * fs;
      s.increasing = false;
      break;
    }
    case Effect::kGaussMarkov:
      p["correlation_time_s"] = LogUniform(u[0], 20.0 * tau0, T / 100.0);
      s.parameter = "sigma_rad_per_s";
      s.lo = 1e-6 * s0;
      s.hi = 1e2 * s0;
      break;
    case Effect::kRandomTelegraph:
      p["mean_dwell_s"] = LogUniform(u[0], 20.0 * tau0, T / 100.0);
      s.parameter = "amplitude_rad_per_s";
      s.lo = 1e-6 * s0;
      s.hi = 1e2 * s0;
      break;
    case Effect::kHarmonic:
      p["frequency_hz"] = LogUniform(u[0], 20.0 / T, fs / 5.0);
      s.parameter = "amplitude_rad_per_s";
      s.lo = 1e-6 * s0;
      s.hi = 1e2 * s0;
      break;
    case Effect::kAngleQuantization:
      s.parameter = "lsb_rad";
      s.lo = 1e-3 * s0 * tau0;
      s.hi = 3.0 * s0 * tau0;
      break;
    case Effect::kRateQuantization:
      s.parameter = "lsb_rad_per_s";
      s.lo = 1e-3 * s0;
      s.hi = 2.0 * s0;
      break;
    case Effect::kExponentialDrift:
      p["time_constant_s"] = LogUniform(u[0], T / 50.0, T / 2.0);
      s.parameter = "amplitude_rad_per_s";
      s.lo = 1e-6 * s0;
      s.hi = 1e2 * s0;
      break;
    case Effect::kBiasStep:
      p["time_s"] = T * (0.1 + 0.8 * u[0]);
      s.parameter = "size_rad_per_s";
      s.lo = 1e-6 * s0;
      s.hi = 1e2 * s0;
      break;
    case Effect::kResonance:
      p["frequency_hz"] = LogUniform(u[0], 20.0 / T, fs / 5.0);
      p["damping"] = 0.05;
      s.parameter = "sigma_rad_per_s";
      s.lo = 1e-6 * s0;
      s.hi = 1e2 * s0;
      break;
    case Effect::kOutliers:
      p["rate_hz"] = LogUniform(u[0], 5.0, 500.0) / T;
      s.parameter = "size_rad_per_s";
      s.lo = 1e-2 * s0;
      s.hi = 1e3 * s0;
      break;
  }
  s.effect.params[s.parameter] = s.lo;
  return s;
}

}  // namespace

bool BenchmarkDrawOptions::IsValid(std::string* why) const {
  if (presets.empty()) {
    *why = "no presets";
    return false;
  }
  if (!(min_duration_s > 0 && max_duration_s >= min_duration_s && min_rate_hz > 0 &&
        max_rate_hz >= min_rate_hz)) {
    *why = "duration and rate ranges must be positive and ordered";
    return false;
  }
  if (max_samples < 4096) {
    *why = "max_samples must be >= 4096";
    return false;
  }
  if (!(control_fraction >= 0.0 && control_fraction <= 1.0)) {
    *why = "control_fraction must be in [0, 1]";
    return false;
  }
  if (!(weak_weight >= 0 && borderline_weight >= 0 && clear_weight >= 0 &&
        weak_weight + borderline_weight + clear_weight > 0)) {
    *why = "strength class weights must be >= 0 with a positive sum";
    return false;
  }
  return true;
}

std::string StrengthClass(bool control, double z) {
  if (control) return "control";
  if (z < kBorderlineStrength) return "weak";
  if (z < kClearStrength) return "borderline";
  return "clear";
}

std::pair<double, double> BenchmarkCase::ExpectedTauRange(double threshold_z) const {
  double lo = 0.0, hi = 0.0;
  for (std::size_t i = 0; i < tau_s.size(); ++i) {
    if (gap_z[i] < threshold_z) continue;
    if (lo == 0.0) lo = tau_s[i];
    hi = tau_s[i];
  }
  return {lo, hi};
}

bool MeasureStrength(const sim::SensorModel& base, const std::optional<EffectInstance>& effect,
                     std::int64_t n, BenchmarkCase* c, std::string* why) {
  return Measure(MakeGrid(base, n, IsNonStationary(effect)), base, effect, c, why);
}

bool DrawBenchmarkCase(const BenchmarkDrawOptions& o, std::uint64_t seed, int index,
                       BenchmarkCase* c, std::string* why) {
  if (!o.IsValid(why)) return false;
  *c = BenchmarkCase{};
  c->index = index;
  // Every draw is taken, used or not, so that one choice never shifts the others.
  sim::Engine engine = sim::MakeEngine(seed, static_cast<std::uint64_t>(index), 0);
  double u[12];
  for (double& x : u) x = Uniform(engine);
  c->preset = o.presets[std::min(o.presets.size() - 1, static_cast<std::size_t>(u[0] * o.presets.size()))];
  const double duration = LogUniform(u[1], o.min_duration_s, o.max_duration_s);
  double rate_hz = LogUniform(u[2], o.min_rate_hz, o.max_rate_hz);
  c->num_samples = std::llround(duration * rate_hz);
  if (c->num_samples > o.max_samples) {
    c->num_samples = o.max_samples;
    rate_hz = static_cast<double>(o.max_samples) / duration;
  }
  c->sample_clock = SampleClock::FromRateHz(rate_hz);
  sim::SensorModel preset;
  if (!sim::LoadPreset(c->preset, &preset, why)) return false;
  c->base.name = c->preset + "_ieee952";
  c->base.sample_clock = c->sample_clock;
  c->base.terms = preset.terms;  // band-limit and quantizers dropped: they are effects
  if (u[3] < o.control_fraction) {
    c->strength_class = "control";
    return Measure(MakeGrid(c->base, c->num_samples, false), c->base, std::nullopt, c, why);
  }
  constexpr int kEffects = static_cast<int>(std::size(kAllEffects));
  const Effect effect = kAllEffects[std::min(kEffects - 1, static_cast<int>(u[4] * kEffects))];
  const StrengthGrid grid = MakeGrid(c->base, c->num_samples,
                                     effect == Effect::kBiasStep || effect == Effect::kExponentialDrift);
  const double wsum = o.weak_weight + o.borderline_weight + o.clear_weight;
  double lo = kClearStrength, hi = 100.0;
  if (u[5] * wsum < o.weak_weight) {
    lo = 0.3;
    hi = kBorderlineStrength;
  } else if (u[5] * wsum < o.weak_weight + o.borderline_weight) {
    lo = kBorderlineStrength;
    hi = kClearStrength;
  }
  c->target_z = LogUniform(u[6], lo, hi);
  const double s0 = std::sqrt(c->base.ExpectedAvar(1, {c->num_samples, sim::AvarEstimatorKind::kOverlapping}));
  Scaled s = Shape(effect, &u[10], c->sample_clock, static_cast<double>(c->num_samples), s0);
  // The sign of a drift or a step does not change the Allan curve; it does change the record.
  const double sign = (effect == Effect::kExponentialDrift || effect == Effect::kBiasStep) && u[7] < 0.5 ? -1.0 : 1.0;
  auto strength_at = [&](double x, BenchmarkCase* out) {
    EffectInstance e = s.effect;
    e.params[s.parameter] = sign * x;
    std::string w;
    if (!Measure(grid, c->base, e, out, &w)) return -1.0;
    return out->strength_z;
  };
  // Bisection on the log of the parameter: strength is monotone in it.
  BenchmarkCase probe = *c;
  const double at_lo = strength_at(s.increasing ? s.lo : s.hi, &probe);
  const double at_hi = strength_at(s.increasing ? s.hi : s.lo, &probe);
  double x;
  if (at_lo < 0.0 || at_hi < 0.0 || (at_hi < kBorderlineStrength && at_hi < c->target_z)) {
    // Out of reach (an effect the baseline absorbs): the parameter itself is drawn over its
    // range and the strength is whatever it gives.
    x = LogUniform(u[8], s.lo, s.hi);
  } else if (at_hi < c->target_z) {
    x = s.increasing ? s.hi : s.lo;  // as strong as the range allows
  } else if (at_lo > c->target_z) {
    x = s.increasing ? s.lo : s.hi;
  } else {
    double a = std::log(s.lo), b = std::log(s.hi);
    for (int it = 0; it < 16; ++it) {
      const double mid = 0.5 * (a + b);
      const double z = strength_at(std::exp(mid), &probe);
      if ((z < c->target_z) == s.increasing) a = mid; else b = mid;
    }
    x = std::exp(0.5 * (a + b));
  }
  s.effect.params[s.parameter] = sign * x;
  c->effect = s.effect;
  if (!Measure(grid, c->base, c->effect, c, why)) return false;
  c->strength_class = StrengthClass(false, c->strength_z);
  return true;
}

}  // namespace allanlab::experiments
