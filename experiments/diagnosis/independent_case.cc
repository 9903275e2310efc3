#include "experiments/diagnosis/independent_case.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

#include "estimators/allan_variance.h"
#include "independent/allan_forms.h"
#include "independent/generate.h"
#include "independent/random_stream.h"

namespace allanlab::experiments {
namespace {

using namespace independent;

constexpr double kDeg = M_PI / 180.0;
constexpr double kBorderlineLow = 3.0, kClearLow = 10.0, kClearHigh = 60.0;

double LogUniform(double u, double lo, double hi) { return lo * std::pow(hi / lo, u); }

// The tau grid of the strength: 10 points per decade, m from 1 to n/4.
std::vector<std::int64_t> GridFactors(std::int64_t n) {
  std::vector<std::int64_t> ms;
  for (int i = 0;; ++i) {
    const auto m = static_cast<std::int64_t>(std::llround(std::pow(10.0, i / 10.0)));
    if (m > n / 4) break;
    if (ms.empty() || m != ms.back()) ms.push_back(m);
  }
  return ms;
}

// What every trial value of one case's strength parameter shares.
struct Context {
  std::int64_t n = 0;
  std::vector<std::int64_t> ms;
  std::vector<double> tau, nu, e_base;
  double block_avar = 0.0;  // base AVAR at the block length of a step or drift (0: none)
  // Compare with the user's model refitted to base + effect (synthetic records), or with the base
  // curve itself (a real recording: its own curve fits no IEEE model, so only the change the
  // effect makes to it is the effect's strength).
  bool refit_user_model = true;
};

// The effect's own Allan variance on the grid: the recipe with the sensor's noise removed, and
// for a low-pass the change it makes to the white noise.
std::vector<double> EffectAvar(const Recipe& base, const Recipe& full, const Context& c) {
  Recipe only = full;
  only.noise = Noise{};
  only.low_pass = LowPass{};
  std::vector<double> d = ExpectedOavar(only, c.ms, c.n);
  if (full.low_pass.design != LowPassDesign::kNone) {
    for (std::size_t i = 0; i < c.ms.size(); ++i) d[i] += WhiteChainAvar(full, c.ms[i]) - WhiteChainAvar(base, c.ms[i]);
  }
  // A quantizer's error replaces part of the signal rather than adding to it only in the coarse
  // regime the draws avoid; its approximate share is what allan_forms.h gives.
  return d;
}

// Nonnegative weighted least squares of N^2/tau + floor^2 + K^2 tau/3 to e (relative residuals,
// weights nu/2): every subset of the three terms solved, the best feasible kept.
std::vector<double> FitUserModel(const Context& c, const std::vector<double>& e) {
  const std::size_t k = c.ms.size();
  Eigen::MatrixXd a(k, 3);
  Eigen::VectorXd b(k);
  for (std::size_t i = 0; i < k; ++i) {
    const double w = std::sqrt(c.nu[i] / 2.0) / e[i];
    a(i, 0) = w / c.tau[i];
    a(i, 1) = w;
    a(i, 2) = w * c.tau[i] / 3.0;
    b(i) = w * e[i];
  }
  double best = std::numeric_limits<double>::infinity();
  Eigen::Vector3d coef = Eigen::Vector3d::Zero();
  for (int mask = 1; mask < 8; ++mask) {
    std::vector<int> cols;
    for (int j = 0; j < 3; ++j) {
      if (mask & (1 << j)) cols.push_back(j);
    }
    Eigen::MatrixXd sub(k, cols.size());
    for (std::size_t j = 0; j < cols.size(); ++j) sub.col(static_cast<Eigen::Index>(j)) = a.col(cols[j]);
    const Eigen::VectorXd x = sub.colPivHouseholderQr().solve(b);
    if ((x.array() < 0.0).any()) continue;
    const double cost = (sub * x - b).squaredNorm();
    if (cost < best) {
      best = cost;
      coef.setZero();
      for (std::size_t j = 0; j < cols.size(); ++j) coef(cols[j]) = x(static_cast<Eigen::Index>(j));
    }
  }
  std::vector<double> fit(k);
  for (std::size_t i = 0; i < k; ++i) fit[i] = coef(0) / c.tau[i] + coef(1) + coef(2) * c.tau[i] / 3.0;
  return fit;
}

// Excess kurtosis of y = lsb round(x / lsb), x ~ N(mean, variance): the levels' probabilities
// summed exactly (Phi differences over every level within 12 sigma).
double RoundedGaussianExcessKurtosis(double lsb, double mean, double variance) {
  const double sd = std::sqrt(variance);
  const auto lo = static_cast<std::int64_t>(std::floor((mean - 12.0 * sd) / lsb)) - 1;
  const auto hi = static_cast<std::int64_t>(std::ceil((mean + 12.0 * sd) / lsb)) + 1;
  auto cdf = [&](double x) { return 0.5 * std::erfc(-(x - mean) / (sd * std::sqrt(2.0))); };
  std::vector<double> p;
  double m1 = 0.0;
  for (std::int64_t k = lo; k <= hi; ++k) {
    const double level = static_cast<double>(k) * lsb;
    p.push_back(cdf(level + 0.5 * lsb) - cdf(level - 0.5 * lsb));
    m1 += p.back() * level;
  }
  double m2 = 0.0, m4 = 0.0;
  for (std::int64_t k = lo; k <= hi; ++k) {
    const double d = static_cast<double>(k) * lsb - m1, w = p[static_cast<std::size_t>(k - lo)];
    m2 += w * d * d;
    m4 += w * d * d * d * d;
  }
  return m2 > 0.0 ? m4 / (m2 * m2) - 3.0 : 0.0;
}

// base_e1: the record's AVAR at m = 1 without the effect, its per-sample variance (white-dominated).
double KurtosisZ(const Recipe& full, const std::string& id, double base_e1, double e1, std::int64_t n) {
  const double v = 2.0 * e1, v2 = v * v, tau0 = full.sample_period_s();
  double excess = 0.0;
  if (id == "outliers" && full.spikes) {
    const Spikes& s = *full.spikes;
    const double p = s.rate_hz * tau0, al = s.tail_index;
    excess = 2.0 * p * std::pow(s.scale_rad_per_s, 4) * al / (al - 4.0) / v2;
  } else if (id == "rate_quantization" && full.rate_quantizer && !full.rate_quantizer->subtractive_dither) {
    // Plain rounding: the samples sit on the grid where the bias puts them, and an LSB beyond ~1.5
    // sigma makes the kurtosis depend on that place (at 2.4 sigma from +0.7 to -0.6, where
    // Sheppard's -2.4 q2^2 / v^2 averaged over it gives -0.06). The increments of iid samples
    // have half their excess kurtosis.
    excess = 0.5 * RoundedGaussianExcessKurtosis(full.rate_quantizer->lsb_rad_per_s, full.noise.bias_rad_per_s, base_e1);
  } else if (id == "rate_quantization" && full.rate_quantizer) {
    const double q2 = std::pow(full.rate_quantizer->lsb_rad_per_s, 2) / 12.0;
    excess = -2.4 * q2 * q2 / v2;
  } else if (id == "angle_quantization" && full.angle_quantizer) {
    const double q2 = std::pow(full.angle_quantizer->lsb_rad / tau0, 2) / 12.0;
    excess = -21.6 * q2 * q2 / v2;
  }
  return std::abs(excess) / std::sqrt(24.0 / static_cast<double>(n));
}

double BlockZ(const Recipe& full, const std::string& id, const Context& c) {
  if (c.block_avar <= 0.0) return 0.0;
  if (id == "bias_step" && full.bias_step) return std::abs(full.bias_step->size_rad_per_s) / std::sqrt(2.0 * c.block_avar);
  if (id == "exponential_drift" && full.warmup_drift) {
    const double change = std::abs(full.warmup_drift->amplitude_rad_per_s) * std::pow(1.0 - std::exp(-1.0), 2);
    return change / std::sqrt(2.0 * c.block_avar);
  }
  return 0.0;
}

void Measure(const Recipe& base, const Recipe& full, const std::string& id, const Context& c, BenchmarkCase* d) {
  const std::vector<double> delta = EffectAvar(base, full, c);
  std::vector<double> e(c.ms.size());
  for (std::size_t i = 0; i < e.size(); ++i) e[i] = std::max(c.e_base[i] + delta[i], 1e-300);
  const std::vector<double> fit = c.refit_user_model ? FitUserModel(c, e) : c.e_base;
  d->tau_s = c.tau;
  d->gap_z.assign(c.ms.size(), 0.0);
  d->oavar_z = d->relative_peak = d->peak_tau_s = 0.0;
  for (std::size_t i = 0; i < e.size(); ++i) {
    if (!(fit[i] > 0.0)) continue;
    const double ratio = e[i] / fit[i];
    d->gap_z[i] = std::abs(std::log(ratio)) * std::sqrt(c.nu[i] / 2.0);
    d->relative_peak = std::max(d->relative_peak, std::abs(ratio - 1.0));
    if (d->gap_z[i] > d->oavar_z) {
      d->oavar_z = d->gap_z[i];
      d->peak_tau_s = c.tau[i];
    }
  }
  d->kurtosis_z = KurtosisZ(full, id, c.e_base.front(), e.front(), c.n);
  d->halves_z = BlockZ(full, id, c);
  d->halves_peak_tau_s = 0.0;
  if (d->halves_z > 0.0) {
    const double t = full.bias_step ? std::min(full.bias_step->time_s, static_cast<double>(c.n) / full.rate_hz -
                                                                           full.bias_step->time_s)
                                    : full.warmup_drift->time_constant_s;
    d->halves_peak_tau_s = t;
  }
  d->strength_z = std::max({d->oavar_z, d->kurtosis_z, d->halves_z});
}

Context MakeContext(const Recipe& base, const Recipe& full, std::int64_t n) {
  Context c;
  c.n = n;
  c.ms = GridFactors(n);
  const double tau0 = base.sample_period_s();
  for (std::int64_t m : c.ms) {
    c.tau.push_back(static_cast<double>(m) * tau0);
    c.nu.push_back(std::max(1.0, 0.75 * static_cast<double>(n) / static_cast<double>(m)));
  }
  c.e_base = ExpectedOavar(base, c.ms, n);
  double block_s = 0.0;
  if (full.bias_step) {
    block_s = std::min(full.bias_step->time_s, static_cast<double>(n) * tau0 - full.bias_step->time_s);
  } else if (full.warmup_drift) {
    block_s = full.warmup_drift->time_constant_s;
  }
  if (block_s > 0.0) {
    const std::int64_t m = std::clamp<std::int64_t>(std::llround(block_s / tau0), 1, n / 2);
    c.block_avar = ExpectedOavar(base, m, n);
  }
  return c;
}

// One effect family member with its strength parameter x in [lo, hi].
struct Variant {
  std::string design;
  std::function<void(double x, Recipe*)> apply;
  double lo = 0.0, hi = 0.0;
  bool increasing = true;
  bool solvable = true;  // false: no strength parameter (x unused)
};

Variant MakeVariant(const std::string& id, RandomStream& u, const Recipe& base, std::int64_t n, double s0) {
  const double fs = base.rate_hz, tau0 = base.sample_period_s(), T = static_cast<double>(n) * tau0;
  Variant v;
  const double sign = u.Uniform() < 0.5 ? -1.0 : 1.0;
  if (id == "bandwidth") {
    static const char* kNames[] = {"lp1_impulse_invariant", "lp1_bilinear", "lp2_impulse_invariant", "lp2_bilinear", "cic"};
    static const LowPassDesign kDesigns[] = {LowPassDesign::kFirstOrderImpulseInvariant, LowPassDesign::kFirstOrderBilinear,
                                             LowPassDesign::kSecondOrderImpulseInvariant, LowPassDesign::kSecondOrderBilinear,
                                             LowPassDesign::kCic};
    const int which = std::min(4, static_cast<int>(u.Uniform() * 5));
    const int l = 4 << std::min(2, static_cast<int>(u.Uniform() * 3));
    const Decimation dec = u.Uniform() < 0.5 ? Decimation::kPoint : Decimation::kAverage;
    const int stages = 2 + std::min(2, static_cast<int>(u.Uniform() * 3));
    v.design = std::string(kNames[which]) + (which == 4 ? "_" + std::to_string(stages) + "x" + std::to_string(l)
                                                        : std::string(dec == Decimation::kPoint ? "_point" : "_average") +
                                                              "_L" + std::to_string(l));
    const LowPassDesign design = kDesigns[which];
    v.apply = [=](double x, Recipe* r) { r->low_pass = LowPass{design, x, l, dec, stages}; };
    v.lo = fs / 40.0;
    v.hi = std::min(0.45 * l * fs, 2.0 * fs);
    v.increasing = false;
    v.solvable = which != 4;
  } else if (id == "gauss_markov") {
    const double tc = LogUniform(u.Uniform(), 20.0 * tau0, T / 50.0);
    v.design = "averaged_ou";
    v.apply = [=](double x, Recipe* r) { r->gauss_markov = GaussMarkov{x, tc}; };
    v.lo = 1e-4 * s0;
    v.hi = 1e2 * s0;
  } else if (id == "random_telegraph") {
    const double dwell = LogUniform(u.Uniform(), 20.0 * tau0, T / 50.0);
    v.design = "poisson_flips";
    v.apply = [=](double x, Recipe* r) { r->telegraph = Telegraph{x, dwell}; };
    v.lo = 1e-4 * s0;
    v.hi = 1e2 * s0;
  } else if (id == "harmonic") {
    const double f = LogUniform(u.Uniform(), 20.0 / T, fs / 5.0);
    v.design = "sinusoid_random_phase";
    v.apply = [=](double x, Recipe* r) { r->sinusoid = Sinusoid{x, f, std::nullopt}; };
    v.lo = 1e-4 * s0;
    v.hi = 1e2 * s0;
  } else if (id == "resonance") {
    const double f0 = fs * (0.1 + 0.3 * u.Uniform()), zeta = LogUniform(u.Uniform(), 0.01, 0.2);
    v.design = "damped_oscillator";
    v.apply = [=](double x, Recipe* r) { r->resonance = Resonance{x, f0, zeta}; };
    v.lo = 1e-4 * s0;
    v.hi = 1e2 * s0;
  } else if (id == "angle_quantization") {
    v.design = "angle_with_carry";
    v.apply = [](double x, Recipe* r) { r->angle_quantizer = AngleQuantizer{x}; };
    v.lo = 1e-3 * s0 * tau0;
    v.hi = 3.0 * s0 * tau0;
  } else if (id == "rate_quantization") {
    const bool dither = u.Uniform() < 0.5;
    v.design = dither ? "rate_subtractive_dither" : "rate_rounding";
    v.apply = [=](double x, Recipe* r) { r->rate_quantizer = RateQuantizer{x, dither}; };
    v.lo = 1e-3 * s0;
    v.hi = 5.0 * s0;  // an LSB up to 5 sigma: the kurtosis z leaves Sheppard's regime there (approximate)
  } else if (id == "exponential_drift") {
    const double td = LogUniform(u.Uniform(), T / 50.0, T / 3.0);
    v.design = "averaged_exponential";
    v.apply = [=](double x, Recipe* r) { r->warmup_drift = WarmupDrift{sign * x, td}; };
    v.lo = 1e-4 * s0;
    v.hi = 1e2 * s0;
  } else if (id == "bias_step") {
    const double t = T * (0.1 + 0.8 * u.Uniform());
    v.design = "step";
    v.apply = [=](double x, Recipe* r) { r->bias_step = BiasStep{sign * x, t}; };
    v.lo = 1e-4 * s0;
    v.hi = 1e2 * s0;
  } else {  // outliers
    const double count = LogUniform(u.Uniform(), 5.0, 200.0), tail = 4.5 + 5.5 * u.Uniform();
    const bool one_sided = u.Uniform() < 0.5;
    v.design = one_sided ? "spikes_one_sided_pareto" : "spikes_two_sided_pareto";
    v.apply = [=](double x, Recipe* r) { r->spikes = Spikes{count / T, x, tail, one_sided}; };
    v.lo = 0.5 * s0;
    v.hi = 1e3 * s0;
  }
  return v;
}

// The strength parameter that gives the target strength, or the strongest its range allows.
// Strength need not be monotone in the parameter (a low-pass far below the sample rate turns
// into something the user's model absorbs), so the range is scanned from its weak end on a log
// grid and the first crossing of the target refined by bisection.
double Solve(const Variant& v, const Recipe& base, const std::string& id, const Context& ctx, double target) {
  if (!v.solvable) return v.lo;
  BenchmarkCase probe;
  auto strength_at = [&](double log_x) {
    Recipe trial = base;
    v.apply(std::exp(log_x), &trial);
    Measure(base, trial, id, ctx, &probe);
    return probe.strength_z;
  };
  const double weak = std::log(v.increasing ? v.lo : v.hi), strong = std::log(v.increasing ? v.hi : v.lo);
  constexpr int kScan = 16;
  double prev = weak, best = weak, best_z = strength_at(weak);
  if (best_z >= target) return std::exp(weak);
  for (int k = 1; k <= kScan; ++k) {
    const double x = weak + (strong - weak) * k / kScan, z = strength_at(x);
    if (z >= target) {
      double a = prev, b = x;  // strength(a) < target <= strength(b)
      for (int it = 0; it < 14; ++it) {
        const double mid = 0.5 * (a + b);
        if (strength_at(mid) < target) a = mid; else b = mid;
      }
      return std::exp(0.5 * (a + b));
    }
    if (z > best_z) {
      best_z = z;
      best = x;
    }
    prev = x;
  }
  return std::exp(best);
}

std::string ParamsOf(const Recipe& r, const std::string& design) {
  char b[512];
  std::string s = "design=" + design;
  auto add = [&](const char* name, double v) {
    std::snprintf(b, sizeof b, ";%s=%.6g", name, v);
    s += b;
  };
  if (r.low_pass.design != LowPassDesign::kNone) add("cutoff_hz", r.low_pass.cutoff_hz);
  if (r.gauss_markov) {
    add("sigma_rad_per_s", r.gauss_markov->sigma_rad_per_s);
    add("correlation_time_s", r.gauss_markov->correlation_time_s);
  }
  if (r.telegraph) {
    add("amplitude_rad_per_s", r.telegraph->amplitude_rad_per_s);
    add("mean_dwell_s", r.telegraph->mean_dwell_s);
  }
  if (r.sinusoid) {
    add("amplitude_rad_per_s", r.sinusoid->amplitude_rad_per_s);
    add("frequency_hz", r.sinusoid->frequency_hz);
  }
  if (r.resonance) {
    add("sigma_rad_per_s", r.resonance->sigma_rad_per_s);
    add("frequency_hz", r.resonance->frequency_hz);
    add("damping_ratio", r.resonance->damping_ratio);
  }
  if (r.angle_quantizer) add("lsb_rad", r.angle_quantizer->lsb_rad);
  if (r.rate_quantizer) add("lsb_rad_per_s", r.rate_quantizer->lsb_rad_per_s);
  if (r.warmup_drift) {
    add("amplitude_rad_per_s", r.warmup_drift->amplitude_rad_per_s);
    add("time_constant_s", r.warmup_drift->time_constant_s);
  }
  if (r.bias_step) {
    add("size_rad_per_s", r.bias_step->size_rad_per_s);
    add("time_s", r.bias_step->time_s);
  }
  if (r.spikes) {
    add("rate_hz", r.spikes->rate_hz);
    add("scale_rad_per_s", r.spikes->scale_rad_per_s);
    add("tail_index", r.spikes->tail_index);
  }
  return s;
}

}  // namespace

bool IndependentDrawOptions::IsValid(std::string* why) const {
  if (!(rate_hz > 0.0 && std::isfinite(rate_hz))) {
    *why = "the rate must be positive";
    return false;
  }
  if (!(min_duration_s > 0.0 && max_duration_s >= min_duration_s && std::isfinite(max_duration_s))) {
    *why = "duration range must be positive and ordered";
    return false;
  }
  if (min_duration_s * rate_hz < 4096) {
    *why = "records must hold at least 4096 samples (raise --min-duration or --rate)";
    return false;
  }
  if (!(control_fraction >= 0.0 && control_fraction < 1.0)) {
    *why = "control fraction must be in [0, 1)";
    return false;
  }
  return true;
}

std::vector<std::string> IndependentEffectOrder(bool with_resonance) {
  std::vector<std::string> ids = {"bandwidth",         "gauss_markov",      "random_telegraph",
                                  "harmonic",          "angle_quantization", "rate_quantization",
                                  "exponential_drift", "bias_step",         "outliers"};
  if (with_resonance) ids.push_back("resonance");
  return ids;
}

void MeasureIndependentStrength(const Recipe& base, const Recipe& full, const std::string& id, std::int64_t n,
                                BenchmarkCase* d) {
  Measure(base, full, id, MakeContext(base, full, n), d);
}

bool DrawIndependentCase(const IndependentDrawOptions& o, std::uint64_t seed, int index, IndependentCase* c,
                         std::string* why) {
  if (!o.IsValid(why)) return false;
  *c = IndependentCase{};
  RandomStream u(seed, static_cast<std::uint64_t>(index), 0x1D5EC0DE);
  // Every base draw is taken, used or not, so that one choice never shifts the others.
  double d[8];
  for (double& x : d) x = u.Uniform();
  Recipe& base = c->base;
  base.rate_hz = o.rate_hz;
  base.noise.arw_rad_per_sqrt_s = LogUniform(d[0], 0.05, 0.5) * kDeg / 60.0;        // deg/sqrt(h)
  base.noise.flicker_floor_rad_per_s = LogUniform(d[1], 0.5, 10.0) * kDeg / 3600.0;  // deg/h
  base.noise.rrw_rad_per_s_per_sqrt_s = LogUniform(d[2], 0.5, 10.0) * kDeg / 3600.0 / 60.0;  // deg/h/sqrt(h)
  base.noise.bias_rad_per_s = (d[3] < 0.5 ? -1.0 : 1.0) * LogUniform(d[4], 0.05, 1.0) * kDeg;  // deg/s
  c->num_samples = std::llround(LogUniform(d[5], o.min_duration_s, o.max_duration_s) * o.rate_hz);
  BenchmarkCase& desc = c->descriptor;
  desc.index = index;
  desc.preset = "independent";
  desc.sample_clock = SampleClock::FromRateHz(o.rate_hz);
  desc.num_samples = c->num_samples;
  // The layout: controls spread evenly, effects in turn.
  const double cf = o.control_fraction;
  const bool control = std::floor((index + 1) * cf) > std::floor(index * cf);
  c->recipe = base;
  if (control) {
    desc.strength_class = "control";
    c->design = "control";
    return true;  // no strength: nothing to see
  }
  const int effect_rank = index - static_cast<int>(std::floor((index + 1) * cf));
  const std::vector<std::string> order = IndependentEffectOrder(o.with_resonance);
  const int e = effect_rank % static_cast<int>(order.size()), round = effect_rank / static_cast<int>(order.size());
  c->effect_id = order[static_cast<std::size_t>(e)];
  const bool borderline = round % 4 == 3;
  desc.target_z = borderline ? LogUniform(d[6], kBorderlineLow, kClearLow) : LogUniform(d[6], kClearLow, kClearHigh);
  const double s0 = std::sqrt(ExpectedOavar(base, 1, c->num_samples));
  const Variant v = MakeVariant(c->effect_id, u, base, c->num_samples, s0);
  c->design = v.design;
  const Context ctx = [&] {
    Recipe probe = base;
    v.apply(v.lo, &probe);
    return MakeContext(base, probe, c->num_samples);
  }();
  const double x = Solve(v, base, c->effect_id, ctx, desc.target_z);
  c->recipe = base;
  v.apply(x, &c->recipe);
  if (!c->recipe.IsValid(c->num_samples, why)) {
    *why = "recording " + std::to_string(index) + ": " + *why;
    return false;
  }
  Measure(base, c->recipe, c->effect_id, ctx, &desc);
  desc.strength_class = desc.strength_z >= kClearLow ? "clear" : (desc.strength_z >= kBorderlineLow ? "borderline" : "weak");
  EffectInstance inst;
  if (!ParseEffect(c->effect_id, &inst.effect)) {
    *why = "the diagnosis does not know the effect id " + c->effect_id;
    return false;
  }
  desc.effect = inst;  // the id only: the parameters are the independent generator's (params_text)
  desc.params_text = ParamsOf(c->recipe, v.design);
  return true;
}

bool DrawInjectedCase(std::span<const double> segment, double rate_hz, const std::string& source, std::uint64_t seed,
                      int index, IndependentCase* c, std::vector<double>* record, std::string* why) {
  static const char* kIds[kInjectedEffects] = {"bias_step", "exponential_drift", "outliers",
                                               "harmonic",  "gauss_markov",      "random_telegraph"};
  const auto n = static_cast<std::int64_t>(segment.size());
  if (n < 4096) {
    *why = source + ": a segment needs at least 4096 samples";
    return false;
  }
  *c = IndependentCase{};
  c->num_samples = n;
  c->base.rate_hz = rate_hz;
  c->effect_id = kIds[index % kInjectedEffects];
  RandomStream u(seed, static_cast<std::uint64_t>(index), 0x1A1EC7ED);
  BenchmarkCase& desc = c->descriptor;
  desc.index = index;
  desc.preset = source;
  desc.sample_clock = SampleClock::FromRateHz(rate_hz);
  desc.num_samples = n;
  desc.target_z = LogUniform(u.Uniform(), kClearLow, kClearHigh);
  // The segment's own curve in place of a base model.
  Context ctx;
  ctx.n = n;
  ctx.refit_user_model = false;
  ctx.ms = GridFactors(n);
  for (std::int64_t m : ctx.ms) {
    ctx.tau.push_back(static_cast<double>(m) / rate_hz);
    ctx.nu.push_back(std::max(1.0, 0.75 * static_cast<double>(n) / static_cast<double>(m)));
  }
  ctx.e_base = estimators::AllanVariance(segment, ctx.ms, estimators::AvarEstimatorKind::kOverlapping);
  for (double& e : ctx.e_base) e = std::max(e, 1e-300);
  const double s0 = std::sqrt(ctx.e_base.front());
  const Variant v = MakeVariant(c->effect_id, u, c->base, n, s0);
  c->design = v.design;
  Recipe probe = c->base;
  v.apply(v.lo, &probe);
  double block_s = 0.0;
  if (probe.bias_step) block_s = std::min(probe.bias_step->time_s, static_cast<double>(n) / rate_hz - probe.bias_step->time_s);
  if (probe.warmup_drift) block_s = probe.warmup_drift->time_constant_s;
  if (block_s > 0.0) {
    const std::int64_t m = std::clamp<std::int64_t>(std::llround(block_s * rate_hz), 1, n / 2);
    const std::int64_t one[] = {m};
    ctx.block_avar = estimators::AllanVariance(segment, one, estimators::AvarEstimatorKind::kOverlapping).front();
  }
  const double x = Solve(v, c->base, c->effect_id, ctx, desc.target_z);
  c->recipe = c->base;
  v.apply(x, &c->recipe);
  if (!c->recipe.IsValid(n, why)) return false;
  Measure(c->base, c->recipe, c->effect_id, ctx, &desc);
  desc.strength_class = desc.strength_z >= kClearLow ? "clear" : (desc.strength_z >= kBorderlineLow ? "borderline" : "weak");
  EffectInstance inst;
  if (!ParseEffect(c->effect_id, &inst.effect)) {
    *why = "the diagnosis does not know the effect id " + c->effect_id;
    return false;
  }
  desc.effect = inst;
  desc.params_text = ParamsOf(c->recipe, v.design);
  record->assign(segment.begin(), segment.end());
  Inject(c->recipe, seed, static_cast<std::uint64_t>(index), *record);
  return true;
}

}  // namespace allanlab::experiments
