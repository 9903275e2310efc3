#include "experiments/diagnosis/candidate_estimate.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>
#include <variant>

#include "estimators/fit/parametric_fit.h"
#include "estimators/fit/parametric_term.h"
#include "experiments/diagnosis/line_shape.h"
#include "experiments/diagnosis/resonance_estimate.h"
#include "sim/gauss_markov.h"
#include "sim/quantization_noise.h"

namespace allanlab::experiments {
namespace {

class FlooredBandLimit final : public estimators::ParametricTerm {
 public:
  explicit FlooredBandLimit(std::shared_ptr<const estimators::ParametricTerm> inner, double start_hz = 0.0)
      : inner_(std::move(inner)), start_hz_(start_hz) {}
  std::string_view id() const override { return inner_->id(); }
  std::string_view short_name() const override { return inner_->short_name(); }
  const std::vector<estimators::ParameterSpec>& parameters() const override { return inner_->parameters(); }
  void Bounds(const estimators::AvarCurve& curve, std::vector<double>* lo, std::vector<double>* hi) const override {
    inner_->Bounds(curve, lo, hi);
    (*lo)[0] = std::max((*lo)[0], 0.01 / curve.sample_clock.period_s());
  }
  bool InitialGuess(const estimators::AvarCurve& curve, std::span<const double> avar, const sim::SensorModel& without,
                    std::vector<double>* params, std::string* why) const override {
    if (start_hz_ > 0.0) {
      *params = {start_hz_};
      return true;
    }
    return inner_->InitialGuess(curve, avar, without, params, why);
  }
  void ApplyTo(std::span<const double> p, sim::SensorModel* model) const override { inner_->ApplyTo(p, model); }
  bool modifies_other_terms() const override { return true; }

 private:
  std::shared_ptr<const estimators::ParametricTerm> inner_;
  double start_hz_ = 0.0;  // a start from the record (> 0), else the inner term's screen
};

double Median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

std::vector<double> BlockMeans(std::span<const double> y, std::size_t blocks) {
  const std::size_t m = y.size() / blocks;
  std::vector<double> means(blocks, 0.0);
  for (std::size_t b = 0; b < blocks; ++b) {
    double s = 0.0;
    for (std::size_t k = 0; k < m; ++k) s += y[b * m + k];
    means[b] = s / static_cast<double>(m);
  }
  return means;
}

// The tau where the curve rises most above the baseline, relative to it.
std::optional<EffectInstance> Bump(Effect effect, const EstimateInputs& in, std::string* why) {
  const auto& c = *in.curve;
  int best = -1;
  double best_ratio = 0.0;
  for (std::size_t i = 0; i < c.size(); ++i) {
    const double ratio = (c.avar[i] - in.baseline_avar[i]) / in.baseline_avar[i];
    if (ratio > best_ratio) {
      best_ratio = ratio;
      best = static_cast<int>(i);
    }
  }
  if (best < 0) {
    *why = "the curve never rises above the baseline";
    return std::nullopt;
  }
  // The OU Allan variance peaks (in tau * AVAR, i.e. where it dominates a white floor most) near
  // tau = 1.89 Tc, as the first-order low-pass of docs/theory.md §2.9.
  const double tc = c.tau_s[best] / 1.89;
  sim::GaussMarkov unit;
  unit.sigma_rad_per_s = 1.0;
  unit.correlation_time_s = tc;
  const sim::RecordShape shape{c.num_samples, c.estimator};
  const double s = unit.ExpectedAvar(c.m[best], c.sample_clock.period_s(), shape);
  const double sigma = std::sqrt((c.avar[best] - in.baseline_avar[best]) / s);
  EffectInstance e{effect, {}};
  if (effect == Effect::kGaussMarkov) {
    e.params = {{"sigma_rad_per_s", sigma}, {"correlation_time_s", tc}};
  } else {
    e.params = {{"amplitude_rad_per_s", sigma}, {"mean_dwell_s", 2.0 * tc}};
  }
  return e;
}

// A random telegraph whose two levels the record shows: for the shortest blocks (of 4, 8, ...
// samples) whose means fall into two clusters at least kLevelSeparation of their spread apart
// (an equal-variance two-Gaussian mixture fitted by EM from the halves about the median), the
// amplitude is half the distance between the clusters and the mean dwell comes from the share f of
// neighbouring blocks on different levels: for flips at rate 1/dwell, f = (1 - e^{-2 d / dwell}) / 2
// at a block length d. Gaussian wander (a Gauss-Markov, a random walk) and a sinusoid do not come
// near that separation; a step does, with one change of level, hence the kMinLevelChanges.
struct TwoLevels {
  double amplitude = 0.0, mean_dwell_s = 0.0, separation_sd = 0.0;
};
constexpr double kLevelSeparation = 8.0;
constexpr int kMinLevelChanges = 8;

std::optional<TwoLevels> SeenTwoLevels(std::span<const double> y, double tau0) {
  const std::size_t n = y.size();
  for (std::size_t m = 4; n / m >= 256; m *= 2) {
    const std::size_t blocks = n / m;
    std::vector<double> b(blocks, 0.0);
    for (std::size_t k = 0; k < blocks; ++k) {
      for (std::size_t j = 0; j < m; ++j) b[k] += y[k * m + j];
      b[k] /= static_cast<double>(m);
    }
    const double median = Median(b);
    double sum_below = 0.0, sum_above = 0.0, below = 0.0;
    for (double v : b) {
      if (v < median) {
        sum_below += v;
        below += 1.0;
      } else {
        sum_above += v;
      }
    }
    if (below < 1.0 || below > static_cast<double>(blocks) - 1.0) continue;
    double mu1 = sum_below / below, mu2 = sum_above / (static_cast<double>(blocks) - below), w2 = 0.5, var = 0.0;
    for (double v : b) var += std::pow(v - (v < median ? mu1 : mu2), 2);
    var /= static_cast<double>(blocks);
    std::vector<double> r(blocks);  // each block's responsibility of the upper level
    for (int it = 0; it < 50 && var > 0.0; ++it) {
      double r_sum = 0.0, r_x = 0.0, q_x = 0.0;
      for (std::size_t k = 0; k < blocks; ++k) {
        const double log_odds = (std::pow(b[k] - mu1, 2) - std::pow(b[k] - mu2, 2)) / (2.0 * var) + std::log(w2 / (1.0 - w2));
        r[k] = 1.0 / (1.0 + std::exp(-std::clamp(log_odds, -700.0, 700.0)));
        r_sum += r[k];
        r_x += r[k] * b[k];
        q_x += (1.0 - r[k]) * b[k];
      }
      if (!(r_sum > 0.5 && r_sum < static_cast<double>(blocks) - 0.5)) break;
      w2 = r_sum / static_cast<double>(blocks);
      mu2 = r_x / r_sum;
      mu1 = q_x / (static_cast<double>(blocks) - r_sum);
      var = 0.0;
      for (std::size_t k = 0; k < blocks; ++k) var += r[k] * std::pow(b[k] - mu2, 2) + (1.0 - r[k]) * std::pow(b[k] - mu1, 2);
      var /= static_cast<double>(blocks);
    }
    if (!(var > 0.0)) continue;
    const double separation = std::abs(mu2 - mu1) / std::sqrt(var);
    if (separation < kLevelSeparation || std::min(w2, 1.0 - w2) < 0.1) continue;
    const double mid = 0.5 * (mu1 + mu2);
    int changes = 0;
    for (std::size_t k = 1; k < blocks; ++k) changes += (b[k] > mid) != (b[k - 1] > mid) ? 1 : 0;
    const double f = static_cast<double>(changes) / static_cast<double>(blocks - 1);
    if (changes < kMinLevelChanges || f >= 0.45) return std::nullopt;  // longer blocks see no more
    const double block_s = static_cast<double>(m) * tau0;
    return TwoLevels{0.5 * std::abs(mu2 - mu1), -2.0 * block_s / std::log1p(-2.0 * f), separation};
  }
  return std::nullopt;
}

// Lag-1..4 autocorrelation of the record's short-lag part: each minus the mean correlation at
// lags 8..15, where a band-limit near the output rate has none left but slow terms (random walk,
// flicker) still add about the same.
std::vector<double> ShortCorrelation(std::span<const double> y) {
  const std::size_t n = std::min<std::size_t>(y.size(), std::size_t{1} << 21);
  double mean = 0.0;
  for (std::size_t k = 0; k < n; ++k) mean += y[k];
  mean /= static_cast<double>(n);
  std::vector<double> r(16, 0.0);
  for (std::size_t j = 0; j < r.size(); ++j) {
    for (std::size_t k = j; k < n; ++k) r[j] += (y[k] - mean) * (y[k - j] - mean);
  }
  double slow = 0.0;
  for (std::size_t j = 8; j < 16; ++j) slow += r[j] / r[0] / 8.0;
  std::vector<double> rho;
  for (std::size_t j = 1; j <= 4; ++j) rho.push_back(r[j] / r[0] - slow);
  return rho;
}

// The family's cutoff whose white-noise output has the measured lag-1 correlation (by bisection
// in log fc on [fs/100, fs/2], where the correlation falls with fc), and how far the family's
// lags 2..4 then are from the measured ones (sum of squares); false if no cutoff there gives it.
bool MatchCorrelation(const sim::BandLimitFamily& f, std::span<const double> rho, double fs, double* fc,
                      double* misfit) {
  auto predicted = [&](double cutoff, std::vector<double>* out) {
    sim::SensorModel m;
    m.sample_clock = SampleClock::FromRateHz(fs);
    m.terms = {sim::WhiteRateNoise{1.0}};
    m.band_limit = {f.kind, cutoff, f.oversampling, f.sampling};
    std::string invalid;
    if (!m.band_limit.IsValid(fs, &invalid)) return false;
    const std::vector<double> r = m.GaussianAutocovariance(5);
    out->clear();
    for (std::size_t j = 1; j < 5; ++j) out->push_back(r[j] / r[0]);
    return true;
  };
  double lo = fs / 100.0, hi = 0.5 * fs;
  std::vector<double> p_lo, p_hi, p;
  if (!predicted(lo, &p_lo) || !predicted(hi, &p_hi) || !(p_lo[0] > rho[0] && rho[0] > p_hi[0])) return false;
  for (int i = 0; i < 40; ++i) {
    const double mid = std::sqrt(lo * hi);
    if (!predicted(mid, &p)) return false;
    (p[0] > rho[0] ? lo : hi) = mid;
  }
  *fc = std::sqrt(lo * hi);
  if (!predicted(*fc, &p)) return false;
  *misfit = 0.0;
  for (std::size_t j = 1; j < 4; ++j) *misfit += (p[j] - rho[j]) * (p[j] - rho[j]);
  return true;
}

// The band-limit as the fit library measures it: the IEEE 952 terms plus a low-pass fitted
// jointly by GLS, for the filter families (sim::BandLimitFamilies(): first and second order,
// analog point-sampled or averaged, digital bilinear or impulse-invariant, moving average, CIC)
// the record or curve favours; the lowest chi2 names the family and gives fc. A maximum of the
// short-tau ADEV (the seed paper's inflection) is not needed: averaged or slowly sampled outputs
// have none, yet their curve still bends below the white level. A band-limited fit costs
// seconds (minutes wandering to low cutoffs: long filter chains), so only three families are
// fitted: with the record, those whose white-noise correlation at lags 2..4, at the cutoff that
// matches the record's lag 1, is closest to the record's (a decimator's box leaves lag 2 at 0
// where a low-pass leaves rho1^2), plus the best of the cheap screen against the baseline's
// terms; from a curve, the screen's best three.
std::optional<EffectInstance> Bandwidth(const estimators::AvarCurve& curve, const sim::SensorModel* baseline,
                                        std::span<const estimators::Coefficient> fitted_terms,
                                        std::span<const double> record, std::string* why) {
  const auto& families = sim::BandLimitFamilies();
  const double fs = curve.sample_clock.rate_hz();
  std::vector<std::pair<double, std::size_t>> screened;  // (screen SSE ratio, family)
  std::vector<double> screen_fc(families.size(), 0.0);
  for (std::size_t f = 0; f < families.size(); ++f) {
    double ratio = 0.0;
    if (baseline == nullptr) {
      screened.emplace_back(0.0, f);
    } else if (estimators::ScreenBandLimit(families[f].kind, families[f].sampling, families[f].oversampling, curve,
                                           *baseline, &screen_fc[f], &ratio)) {
      screened.emplace_back(ratio, f);
    }
  }
  std::stable_sort(screened.begin(), screened.end());
  std::vector<std::pair<std::size_t, double>> chosen;  // (family, start fc; 0: the term's screen)
  if (record.size() >= 4096) {
    const std::vector<double> rho = ShortCorrelation(record);
    std::vector<std::tuple<double, std::size_t, double>> matched;  // (misfit, family, fc)
    for (std::size_t f = 0; f < families.size(); ++f) {
      double fc = 0.0, misfit = 0.0;
      if (MatchCorrelation(families[f], rho, fs, &fc, &misfit)) matched.emplace_back(misfit, f, fc);
    }
    std::stable_sort(matched.begin(), matched.end());
    for (std::size_t i = 0; i < matched.size() && chosen.size() < 2; ++i) {
      chosen.emplace_back(std::get<1>(matched[i]), std::get<2>(matched[i]));
    }
  }
  for (const auto& [ratio, f] : screened) {
    if (chosen.size() >= 3) break;
    if (std::none_of(chosen.begin(), chosen.end(), [&](const auto& c) { return c.first == f; })) chosen.emplace_back(f, 0.0);
  }
  std::optional<EffectInstance> best;
  double best_chi2 = 0.0;
  *why = "no cutoff improves the fit of the short taus";
  for (const auto& [f, start_fc] : chosen) {
    const EffectInstance start{Effect::kBandwidth,
                               {{"cutoff_hz", 1.0}, {"order", families[f].order}, {"family", static_cast<double>(f)}}};
    std::shared_ptr<const estimators::ParametricTerm> term = DiagnosisBandLimitTerm(start, start_fc);
    estimators::ParametricFitOptions po;
    po.method = estimators::FitMethod::kGls;
    po.max_iterations = 50;  // a starting value: the candidate's refit polishes it
    if (!fitted_terms.empty()) po.terms.assign(fitted_terms.begin(), fitted_terms.end());
    po.extra = {term};
    estimators::ParametricFitSummary ps;
    if (!estimators::FitAvarModelWithTerms(po, curve, &ps)) {
      po.method = estimators::FitMethod::kWls;
      if (!estimators::FitAvarModelWithTerms(po, curve, &ps)) {
        *why = "band-limited fit failed: " + ps.base.message;
        continue;
      }
    }
    if (ps.extra.empty() || !ps.extra[0].fitted || ps.extra[0].value_si.empty()) {
      *why = "band-limited fit left the cutoff out" + (ps.extra.empty() ? std::string() : ": " + ps.extra[0].note);
      continue;
    }
    if (!best || ps.base.chi2 < best_chi2) {
      best_chi2 = ps.base.chi2;
      best = start;
      best->params["cutoff_hz"] = ps.extra[0].value_si[0];
    }
  }
  return best;
}

std::optional<EffectInstance> Harmonic(std::span<const double> y, double tau0, std::string* why) {
  std::size_t n = 0;
  const std::vector<double> power = HannPeriodogram(y, &n);
  if (power.empty()) {
    *why = "record too short for a periodogram";
    return std::nullopt;
  }
  constexpr std::size_t kHalfWidth = 32;
  std::size_t best = 0;
  double best_ratio = 0.0;
  for (std::size_t b = 4; b + 4 < power.size(); ++b) {
    std::vector<double> around;
    for (std::size_t j = b > kHalfWidth ? b - kHalfWidth : 1; j <= std::min(power.size() - 1, b + kHalfWidth); ++j) {
      if (j + 3 < b || j > b + 3) around.push_back(power[j]);
    }
    const double ratio = power[b] / std::max(Median(around), 1e-300);
    if (ratio > best_ratio) {
      best_ratio = ratio;
      best = b;
    }
  }
  // A Hann-windowed periodogram of Gaussian noise exceeds 30 x its local median at one of 2^19
  // bins with probability ~ 2^19 e^{-30 ln 2} ~ 1e-4 (exponential power, median ln 2).
  if (best_ratio < 30.0) {
    *why = "no spectral line stands out of the periodogram";
    return std::nullopt;
  }
  // Sum the line's power over its main lobe (+-2 bins) so off-bin frequencies are not lost.
  double lobe = 0.0;
  for (std::size_t b = best - 2; b <= best + 2; ++b) lobe += power[b];
  // Hann: sum w^2 = 3/8 n; a sinusoid A carries |X|^2 summed over the lobe ~ A^2 n sum(w^2) / 4.
  const double w2 = 3.0 / 8.0 * static_cast<double>(n);
  const double amplitude = std::sqrt(4.0 * lobe / (static_cast<double>(n) * w2));
  // The peak between bins: a parabola through the log power of the peak bin and its neighbours
  // (the Hann main lobe is near Gaussian there: without noise off by at most 0.016 bin, computed
  // over offsets 0 to 0.5 bin). At a
  // bin's resolution a 0.0125 Hz sinusoid in a 34-minute record started 2.4 % off, and the
  // Allan curve's nulls at multiples of the period (which the refit does not leave) stayed
  // beyond the threshold.
  const double below = std::log(power[best - 1]), at = std::log(power[best]), above = std::log(power[best + 1]);
  const double curvature = below - 2.0 * at + above;
  const double offset = curvature < 0.0 ? std::clamp(0.5 * (below - above) / curvature, -0.5, 0.5) : 0.0;
  return EffectInstance{Effect::kHarmonic,
                        {{"amplitude_rad_per_s", amplitude},
                         {"frequency_hz", (static_cast<double>(best) + offset) / (static_cast<double>(n) * tau0)}}};
}

// The first differences' variance and excess kurtosis: what the kurtosis view sees at the
// shortest tau.
struct Moments {
  double variance = 0.0;
  double excess_kurtosis = 0.0;
};
Moments DifferenceMoments(std::span<const double> y) {
  const std::size_t n = y.size() - 1;
  double mean = 0.0;
  for (std::size_t k = 0; k < n; ++k) mean += y[k + 1] - y[k];
  mean /= static_cast<double>(n);
  double m2 = 0.0, m4 = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    const double c = (y[k + 1] - y[k] - mean) * (y[k + 1] - y[k] - mean);
    m2 += c;
    m4 += c * c;
  }
  m2 /= static_cast<double>(n);
  m4 /= static_cast<double>(n);
  return {m2, m4 / (m2 * m2) - 3.0};
}

// The value grid of a quantized record: the smallest positive gap between distinct values, if
// (nearly) every value sits on it.
std::optional<double> ValueGrid(std::span<const double> y, std::string* why) {
  std::vector<double> v(y.begin(), y.begin() + std::min<std::size_t>(y.size(), 200000));
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
  if (v.size() < 3 || v.size() > y.size() / 4) {
    *why = "the samples do not sit on a value grid";
    return std::nullopt;
  }
  double lsb = std::numeric_limits<double>::infinity();
  for (std::size_t i = 1; i < v.size(); ++i) lsb = std::min(lsb, v[i] - v[i - 1]);
  std::size_t on_grid = 0;
  for (double x : v) {
    const double k = (x - v[0]) / lsb;
    if (std::abs(k - std::round(k)) < 1e-3) ++on_grid;
  }
  if (on_grid < v.size() * 99 / 100) {
    *why = "the distinct values are not multiples of one step";
    return std::nullopt;
  }
  return lsb;
}

// Without a value grid (noise added after the quantizer, a record rescaled or filtered after it)
// the angle LSB from the baseline's Q: the quantizer adds 3 Q^2 / tau^2 with Q = lsb / sqrt(12)
// when the angle crosses many LSBs (sim/output_quantizer.h), which the Q term takes whole. (When
// the angle moves less than an LSB per sample its error is correlated and Q reads low; the
// refit starts from there.)
std::optional<double> LsbFromBaselineQ(const sim::SensorModel* baseline, std::string* why) {
  if (baseline != nullptr) {
    for (const sim::NoiseTerm& t : baseline->terms) {
      if (const auto* q = std::get_if<sim::QuantizationNoise>(&t); q != nullptr && q->q_rad > 0.0) {
        return q->q_rad * std::sqrt(12.0);
      }
    }
  }
  *why += "; the baseline has no quantization noise either";
  return std::nullopt;
}

// Without a value grid, a quantizer with subtractive dither: its error is uniform, white and
// independent of the signal (sim/output_quantizer.h), so it leaves the Allan curve as more white
// noise and shows only in the law of the samples. The first differences carry the error's
// triangular law (excess kurtosis -0.6) at variance 2 s2, s2 = lsb^2 / 12, beside the Gaussian
// signal's: their excess kurtosis is -2.4 s2^2 / V^2 (V their variance), which gives s2 when it
// stands 3 of its standard errors (sqrt(24 / n)) below 0. At most -0.6: all of V the error's.
std::optional<EffectInstance> DitheredRateQuantization(std::span<const double> y, std::string* why) {
  if (y.size() < 3) {
    *why += "; too few samples for the law of their differences";
    return std::nullopt;
  }
  const auto [v, excess] = DifferenceMoments(y);
  const double n = static_cast<double>(y.size() - 1);
  if (!(excess < -3.0 * std::sqrt(24.0 / n))) {
    *why += "; the first differences are not lighter-tailed than Gaussian (no dithered quantizer)";
    return std::nullopt;
  }
  const double s2 = v * std::sqrt(std::min(-excess, 0.6) / 2.4);
  return EffectInstance{Effect::kRateQuantization,
                        {{"lsb_rad_per_s", std::sqrt(12.0 * s2)}, {"subtractive_dither", 1.0}}};
}

// Least squares of block means on [1, E_b(tw)], E_b the exact mean of e^{-k tau0 / tw} over block
// b (the generator's sample times, sim/exponential_drift.h): returns the residual sum of squares
// and the amplitude.
double DriftFit(const std::vector<double>& means, std::size_t block, double tau0, double tw, double* amplitude) {
  const std::size_t blocks = means.size();
  const double rho = std::exp(-tau0 / tw);
  const double within = -std::expm1(-tau0 * static_cast<double>(block) / tw) /
                        (static_cast<double>(block) * -std::expm1(-tau0 / tw));
  double s11 = 0, s1e = 0, see = 0, s1y = 0, sey = 0;
  std::vector<double> e(blocks);
  for (std::size_t b = 0; b < blocks; ++b) {
    e[b] = std::pow(rho, static_cast<double>(b * block)) * within;
    s11 += 1; s1e += e[b]; see += e[b] * e[b]; s1y += means[b]; sey += e[b] * means[b];
  }
  const double det = s11 * see - s1e * s1e;
  if (!(det > 0)) return std::numeric_limits<double>::infinity();
  const double c0 = (see * s1y - s1e * sey) / det;
  *amplitude = (s11 * sey - s1e * s1y) / det;
  double rss = 0;
  for (std::size_t b = 0; b < blocks; ++b) {
    const double r = means[b] - c0 - *amplitude * e[b];
    rss += r * r;
  }
  return rss;
}

std::optional<EffectInstance> Drift(std::span<const double> y, double tau0, std::string* why) {
  constexpr std::size_t kBlocks = 1024;
  if (y.size() < kBlocks * 4) {
    *why = "record too short";
    return std::nullopt;
  }
  const auto means = BlockMeans(y, kBlocks);
  const std::size_t block = y.size() / kBlocks;
  const double length_s = static_cast<double>(block * kBlocks) * tau0;
  // A log grid of tw (T/100 .. T), then golden-section search in ln tw between the best point's
  // neighbours: a warm-up drift is often large against the noise, so a grid-step error in tw
  // (20 %) leaves a gap of its own in every view.
  auto tw_at = [&](double g) { return length_s / 100.0 * std::pow(100.0, g / 24.0); };
  double best_rss = std::numeric_limits<double>::infinity(), best_a = 0.0, best_g = 0.0, a = 0.0;
  for (int g = 0; g <= 24; ++g) {
    const double rss = DriftFit(means, block, tau0, tw_at(g), &a);
    if (rss < best_rss) { best_rss = rss; best_a = a; best_g = g; }
  }
  if (best_a == 0.0) {
    *why = "no exponential trend";
    return std::nullopt;
  }
  double lo = std::max(0.0, best_g - 1.0), hi = std::min(24.0, best_g + 1.0);
  const double phi = 0.5 * (std::sqrt(5.0) - 1.0);
  for (int it = 0; it < 40; ++it) {
    const double g1 = hi - phi * (hi - lo), g2 = lo + phi * (hi - lo);
    double a1 = 0.0, a2 = 0.0;
    if (DriftFit(means, block, tau0, tw_at(g1), &a1) < DriftFit(means, block, tau0, tw_at(g2), &a2)) {
      hi = g2;
    } else {
      lo = g1;
    }
  }
  const double g = 0.5 * (lo + hi);
  if (DriftFit(means, block, tau0, tw_at(g), &a) < best_rss) {
    best_a = a;
    best_g = g;
  }
  return EffectInstance{Effect::kExponentialDrift,
                        {{"amplitude_rad_per_s", best_a}, {"time_constant_s", tw_at(best_g)}}};
}

std::optional<EffectInstance> Step(std::span<const double> y, double tau0, std::string* why) {
  constexpr std::size_t kBlocks = 512;
  if (y.size() < kBlocks * 2) {
    *why = "record too short";
    return std::nullopt;
  }
  const auto means = BlockMeans(y, kBlocks);
  const std::size_t block = y.size() / kBlocks;
  double total = 0.0;
  for (double m : means) total += m;
  double left = 0.0, best = 0.0;
  std::size_t split = 0;
  for (std::size_t k = 1; k < kBlocks; ++k) {
    left += means[k - 1];
    const double m1 = left / k, m2 = (total - left) / (kBlocks - k);
    const double stat = std::abs(m2 - m1) * std::sqrt(static_cast<double>(k) * (kBlocks - k) / kBlocks);
    if (stat > best) { best = stat; split = k; }
  }
  if (split == 0) {
    *why = "no change point";
    return std::nullopt;
  }
  // The same statistic at sample resolution within a block either side of the best block edge
  // (a step mid-block would otherwise leave up to half a block of misplaced offset, and a size
  // diluted by it), over the blocks' whole span.
  const std::size_t n = block * kBlocks;
  double sum_all = 0.0;
  for (std::size_t k = 0; k < n; ++k) sum_all += y[k];
  const std::size_t k_lo = (split - 1) * block, k_hi = std::min(n - 1, (split + 1) * block);
  double prefix = 0.0;
  for (std::size_t k = 0; k < k_lo; ++k) prefix += y[k];
  double best_stat = 0.0, size = 0.0;
  std::size_t best_k = split * block;
  for (std::size_t k = k_lo; k <= k_hi; ++k) {
    if (k > 0) {
      const double m1 = prefix / static_cast<double>(k), m2 = (sum_all - prefix) / static_cast<double>(n - k);
      const double stat = std::abs(m2 - m1) * std::sqrt(static_cast<double>(k) * static_cast<double>(n - k) / n);
      if (stat > best_stat) { best_stat = stat; best_k = k; size = m2 - m1; }
    }
    prefix += y[k];
  }
  return EffectInstance{Effect::kBiasStep,
                        {{"size_rad_per_s", size}, {"time_s", static_cast<double>(best_k) * tau0}}};
}

// A step near `time_s`: the sample k within one block of it where the means of the block after
// and the block before differ most; the size is the difference of the record's means after and
// before k (as Step's).
std::optional<EffectInstance> LocalStep(std::span<const double> y, double tau0, double time_s, double block_s,
                                        std::string* why) {
  const auto n = static_cast<std::int64_t>(y.size());
  const auto block = static_cast<std::int64_t>(std::llround(block_s / tau0));
  const auto centre = static_cast<std::int64_t>(std::llround(time_s / tau0));
  if (block < 1 || 2 * block > n) {
    *why = "record too short for the located step";
    return std::nullopt;
  }
  std::vector<double> prefix(y.size() + 1, 0.0);
  for (std::size_t k = 0; k < y.size(); ++k) prefix[k + 1] = prefix[k] + y[k];
  double best = 0.0;
  std::int64_t best_k = -1;
  for (std::int64_t k = std::max(block, centre - block); k <= std::min(n - block, centre + block); ++k) {
    const double d = (prefix[k + block] - 2.0 * prefix[k] + prefix[k - block]) / static_cast<double>(block);
    if (best_k < 0 || std::abs(d) > std::abs(best)) {
      best = d;
      best_k = k;
    }
  }
  if (best_k < 0) {
    *why = "the located step is at the record's edge";
    return std::nullopt;
  }
  const double before = prefix[best_k] / static_cast<double>(best_k);
  const double after = (prefix[n] - prefix[best_k]) / static_cast<double>(n - best_k);
  return EffectInstance{Effect::kBiasStep,
                        {{"size_rad_per_s", after - before}, {"time_s", static_cast<double>(best_k) * tau0}}};
}

std::optional<EffectInstance> Spikes(std::span<const double> y, double tau0, std::string* why) {
  if (y.size() < 16) {
    *why = "record too short";
    return std::nullopt;
  }
  // A spike a at k gives d_k = a and d_{k +- 1} = -a/2 in d_k = y_k - (y_{k-1} + y_{k+1}) / 2.
  std::vector<double> d(y.size() - 2);
  for (std::size_t k = 1; k + 1 < y.size(); ++k) d[k - 1] = y[k] - 0.5 * (y[k - 1] + y[k + 1]);
  std::vector<double> a(d.size());
  for (std::size_t k = 0; k < d.size(); ++k) a[k] = std::abs(d[k]);
  const double sigma = 1.4826 * Median(a);
  if (!(sigma > 0.0)) {
    *why = "no noise to measure spikes against";
    return std::nullopt;
  }
  // d of a spike carries noise of sd sigma (the MAD above): the detected |d| are a + noise
  // truncated at the threshold, so their median overstates a when a is near it. a is the maximum
  // likelihood value of that truncated normal (grid search).
  const double threshold = 7.0 * sigma;
  std::vector<double> sizes;
  for (std::size_t k = 1; k + 1 < a.size(); ++k) {
    if (a[k] > threshold && a[k] >= a[k - 1] && a[k] >= a[k + 1]) sizes.push_back(a[k]);
  }
  const auto [m2, excess] = DifferenceMoments(y);
  if (sizes.size() < 3) {
    // Heavy tails without isolated spikes: the white noise's law is wider than a Gaussian (a
    // contaminated normal). Its excess kurtosis fixes p a^4 only, so a is set at 3 sd of the
    // differences (their variance barely moves: p a^2 = excess V / 18), when the excess stands
    // 3 of its standard errors (sqrt(24 / n) for a Gaussian) above 0: below the kurtosis view's
    // flag (the Bonferroni threshold, 3.3-3.6 sd), so a departing view has its candidate (at 5,
    // mild tails the view flags, Student-t of 30 dof, were left without one).
    const double n = static_cast<double>(y.size() - 1);
    if (!(excess > 3.0 * std::sqrt(24.0 / n))) {
      *why = "fewer than 3 spikes beyond 7 sigma, and the first differences' excess kurtosis is within 3 "
             "standard errors of 0";
      return std::nullopt;
    }
    const double size = 3.0 * std::sqrt(m2);
    const double p = excess * m2 * m2 / (2.0 * std::pow(size, 4));
    return EffectInstance{Effect::kOutliers, {{"rate_hz", p / tau0}, {"size_rad_per_s", size}}};
  }
  const double largest = *std::max_element(sizes.begin(), sizes.end());
  double size = Median(sizes), best_ll = -std::numeric_limits<double>::infinity();
  // From 2 sigma below the threshold: a spike smaller than that is hardly ever detected, so a few
  // detections cannot place it there.
  const double lowest = threshold - 2.0 * sigma;
  for (int g = 0; g <= 400; ++g) {
    const double s = lowest + (largest - lowest) * g / 400.0;
    const double tail = 0.5 * std::erfc((threshold - s) / (sigma * std::sqrt(2.0)));
    if (!(tail > 0.0)) continue;
    double ll = -static_cast<double>(sizes.size()) * std::log(tail);
    for (double x : sizes) ll -= 0.5 * (x - s) * (x - s) / (sigma * sigma);
    if (ll > best_ll) {
      best_ll = ll;
      size = s;
    }
  }
  // The rate from what the kurtosis view sees: spikes +-a with probability p per sample give the
  // first differences an excess kurtosis 2 p a^4 / V^2 (V their variance; benchmark_case.h), so
  // p = excess V^2 / (2 a^4) places the spikes' fourth moment right even when the count misses
  // the spikes hidden in the noise. The count of detections is the fallback.
  double rate_hz = static_cast<double>(sizes.size()) / (static_cast<double>(y.size()) * tau0);
  const double p = excess * m2 * m2 / (2.0 * std::pow(size, 4));
  if (excess > 0.0 && p > 0.0 && p < 0.1) rate_hz = std::max(rate_hz, p / tau0);
  return EffectInstance{Effect::kOutliers, {{"rate_hz", rate_hz}, {"size_rad_per_s", size}}};
}

}  // namespace

std::shared_ptr<const estimators::ParametricTerm> DiagnosisBandLimitTerm(const EffectInstance& bandwidth,
                                                                         double start_hz) {
  sim::SensorModel probe;
  std::string ignored;
  EffectInstance e = bandwidth;
  e.params["cutoff_hz"] = 1.0;  // the filter's kind and chain only
  if (!AddEffect(e, &probe, &ignored)) probe.band_limit = {sim::LowPassKind::kFirstOrder, 1.0, 8, sim::OutputSampling::kPoint};
  const sim::BandLimit& b = probe.band_limit;
  return std::make_shared<FlooredBandLimit>(estimators::MakeBandLimitTerm(b.kind, b.sampling, b.oversampling), start_hz);
}

std::optional<EffectInstance> BandwidthStart(const EstimateInputs& in, std::string* why) {
  return Bandwidth(*in.curve, in.baseline_model, in.fitted_terms, in.rate_rad_per_s, why);
}
std::optional<EffectInstance> GaussMarkovStart(const EstimateInputs& in, std::string* why) {
  return Bump(Effect::kGaussMarkov, in, why);
}
std::optional<EffectInstance> RandomTelegraphStart(const EstimateInputs& in, std::string* why) {
  if (const auto levels = SeenTwoLevels(in.rate_rad_per_s, in.curve->sample_clock.period_s())) {
    return EffectInstance{Effect::kRandomTelegraph,
                          {{"amplitude_rad_per_s", levels->amplitude},
                           {"mean_dwell_s", levels->mean_dwell_s},
                           {std::string(kLevelSeparationParam), levels->separation_sd}}};
  }
  return Bump(Effect::kRandomTelegraph, in, why);
}
std::optional<EffectInstance> HarmonicStart(const EstimateInputs& in, std::string* why) {
  return Harmonic(in.rate_rad_per_s, in.curve->sample_clock.period_s(), why);
}
std::optional<EffectInstance> AngleQuantizationStart(const EstimateInputs& in, std::string* why) {
  if (const auto lsb = ValueGrid(in.rate_rad_per_s, why)) {
    return EffectInstance{Effect::kAngleQuantization, {{"lsb_rad", *lsb * in.curve->sample_clock.period_s()}}};
  }
  const auto lsb = LsbFromBaselineQ(in.baseline_model, why);
  if (!lsb) return std::nullopt;
  return EffectInstance{Effect::kAngleQuantization, {{"lsb_rad", *lsb}}};
}
std::optional<EffectInstance> RateQuantizationStart(const EstimateInputs& in, std::string* why) {
  if (const auto lsb = ValueGrid(in.rate_rad_per_s, why)) {
    return EffectInstance{Effect::kRateQuantization, {{"lsb_rad_per_s", *lsb}}};
  }
  return DitheredRateQuantization(in.rate_rad_per_s, why);
}
std::optional<EffectInstance> ExponentialDriftStart(const EstimateInputs& in, std::string* why) {
  return Drift(in.rate_rad_per_s, in.curve->sample_clock.period_s(), why);
}
std::optional<EffectInstance> BiasStepStart(const EstimateInputs& in, std::string* why) {
  if (std::isfinite(in.step_time_s) && std::isfinite(in.step_block_s)) {
    return LocalStep(in.rate_rad_per_s, in.curve->sample_clock.period_s(), in.step_time_s, in.step_block_s, why);
  }
  return Step(in.rate_rad_per_s, in.curve->sample_clock.period_s(), why);
}
std::optional<EffectInstance> OutliersStart(const EstimateInputs& in, std::string* why) {
  return Spikes(in.rate_rad_per_s, in.curve->sample_clock.period_s(), why);
}
std::optional<EffectInstance> ResonanceStart(const EstimateInputs& in, std::string* why) {
  if (!in.rate_rad_per_s.empty()) return EstimateResonance(in.rate_rad_per_s, in.curve->sample_clock.period_s(), why);
  // Curve mode: where the term's exact shape best explains the curve above the baseline.
  std::vector<double> residual(in.curve->size()), p;
  for (std::size_t k = 0; k < residual.size(); ++k) residual[k] = in.curve->avar[k] - in.baseline_avar[k];
  if (!estimators::MakeResonanceTerm()->InitialGuess(*in.curve, residual, *in.baseline_model, &p, why)) {
    return std::nullopt;
  }
  return EffectInstance{Effect::kResonance, {{"sigma_rad_per_s", p[0]}, {"frequency_hz", p[1]}, {"damping", p[2]}}};
}

std::optional<double> RecordValueGrid(std::span<const double> rate_rad_per_s) {
  std::string ignored;
  return ValueGrid(rate_rad_per_s, &ignored);
}

std::optional<EffectInstance> EstimateEffect(Effect effect, const EstimateInputs& in, std::string* why) {
  const EffectSpec& spec = SpecOf(effect);
  if (spec.needs_record && in.rate_rad_per_s.empty()) {
    *why = "needs the record (curve mode)";
    return std::nullopt;
  }
  return spec.start(in, why);
}

std::optional<EffectInstance> ShiftEffect(const EffectInstance& e, double offset_s) {
  const EffectSpec& spec = SpecOf(e.effect);
  return spec.shift != nullptr ? spec.shift(e, offset_s) : std::optional<EffectInstance>(e);
}

}  // namespace allanlab::experiments
