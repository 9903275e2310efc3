#include "experiments/diagnosis/gaussian_views.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdlib>
#include <limits>
#include <optional>
#include <type_traits>
#include <utility>
#include <variant>

#include <boost/math/special_functions/trigamma.hpp>

#include "estimators/exact_avar_variance.h"
#include "experiments/diagnosis/gap.h"
#include "experiments/diagnosis/warmup_drift_views.h"
#include "sim/fft.h"

namespace allanlab::experiments {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// n / sum_{|h|<n} (1 - |h|/n) rho(h)^4 for the n increments of the block sums of m samples,
// rho(h) = Cov(D_0, D_h) / Var(D_0) with Cov(D_0, D_h) proportional to the fourth difference of
// V at step m, lag h m (exact_avar_variance.h).
double KurtosisEffectiveCount(const std::vector<long double>& variogram, std::int64_t m, std::int64_t num_samples) {
  const std::int64_t n = num_samples / m - 1;
  if (n < 3) return std::numeric_limits<double>::quiet_NaN();
  auto v = [&](std::int64_t k) { return variogram[static_cast<std::size_t>(std::llabs(k))]; };
  auto cov = [&](std::int64_t k) {
    return static_cast<double>(-(6.0L * v(k) - 4.0L * v(k + m) - 4.0L * v(k - m) + v(k + 2 * m) + v(k - 2 * m)));
  };
  const double c0 = cov(0);
  if (!(c0 > 0.0)) return std::numeric_limits<double>::quiet_NaN();
  double sum = 1.0;
  for (std::int64_t h = 1; h < n; ++h) {
    const double rho = cov(h * m) / c0;
    sum += 2.0 * (1.0 - static_cast<double>(h) / static_cast<double>(n)) * rho * rho * rho * rho;
  }
  return static_cast<double>(n) / sum;
}

// c(d) = sum_k x_{k+d} y_k for d = -(n-1)..n-1 at index d + n - 1 (zero-padded FFTs of length
// 2n; x and y of one length n).
std::vector<double> CrossCorrelation(const std::vector<double>& x, const std::vector<double>& y) {
  const std::size_t n = x.size();
  sim::FftBuffer fx(2 * n + 2), fy(2 * n + 2);
  std::fill(fx.data(), fx.data() + 2 * n + 2, 0.0);
  std::fill(fy.data(), fy.data() + 2 * n + 2, 0.0);
  std::copy(x.begin(), x.end(), fx.data());
  std::copy(y.begin(), y.end(), fy.data());
  sim::ForwardRealFft(2 * n, fx.data());
  sim::ForwardRealFft(2 * n, fy.data());
  for (std::size_t b = 0; b <= n; ++b) fx.complex_data()[b] *= std::conj(fy.complex_data()[b]);
  sim::InverseRealFft(2 * n, fx.data());
  std::vector<double> c(2 * n - 1);
  const double norm = 1.0 / static_cast<double>(2 * n);
  for (std::size_t d = 0; d < n; ++d) c[n - 1 + d] = fx.data()[d] * norm;
  for (std::size_t d = 1; d < n; ++d) c[n - 1 - d] = fx.data()[2 * n - d] * norm;
  return c;
}

// Mean and EDF of the Welch estimate at bin 1 exactly (Isserlis for the complex Gaussian
// X_s = sum_k y_{s S/2 + k} g_k of segment s, g the demeaned window at bin 1):
//   Var((1/K) sum_s |X_s|^2) = (1/K^2) sum_{s,s'} |E X_s conj(X_s')|^2 + |E X_s X_s'|^2,
//   E X_s conj(X_s') = sum_d R(|Delta + d|) Gamma(d),  E X_s X_s' = sum_d R(|Delta + d|) Lambda(d),
// Delta = (s - s') S/2, Gamma(d) = sum_k g_{k+d} conj(g_k), Lambda(d) = sum_k g_{k+d} g_k. At bin
// 1 the spectrum is steepest and the segments' values correlated and not circular, where
// Welch's rule overstated the EDF (controls from independent/ beyond the 1 % quantile above the
// model in 2.2 %).
std::pair<double, double> FirstBinMeanAndEdf(const std::vector<double>& window, const std::vector<double>& r,
                                             std::int64_t segments) {
  const std::size_t s = window.size();
  std::vector<double> a(s), b(s);
  for (std::size_t k = 0; k < s; ++k) {
    const double theta = 2.0 * M_PI * static_cast<double>(k) / static_cast<double>(s);
    a[k] = window[k] * std::cos(theta) + 0.25;  // W(1) = -S/4: the segment mean's share
    b[k] = -window[k] * std::sin(theta);
  }
  const std::vector<double> aa = CrossCorrelation(a, a), bb = CrossCorrelation(b, b);
  const std::vector<double> ab = CrossCorrelation(a, b), ba = CrossCorrelation(b, a);
  const auto half = static_cast<std::int64_t>(s / 2);
  auto moments = [&](std::int64_t delta) {
    std::complex<long double> c1 = 0.0L, c2 = 0.0L;
    for (std::int64_t d = -static_cast<std::int64_t>(s) + 1; d < static_cast<std::int64_t>(s); ++d) {
      const auto i = static_cast<std::size_t>(d + static_cast<std::int64_t>(s) - 1);
      const long double rr = r[static_cast<std::size_t>(std::llabs(delta + d))];
      c1 += rr * std::complex<long double>(aa[i] + bb[i], ba[i] - ab[i]);
      c2 += rr * std::complex<long double>(aa[i] - bb[i], ab[i] + ba[i]);
    }
    return std::norm(c1) + std::norm(c2);
  };
  long double mean = 0.0L;
  for (std::int64_t d = -static_cast<std::int64_t>(s) + 1; d < static_cast<std::int64_t>(s); ++d) {
    const auto i = static_cast<std::size_t>(d + static_cast<std::int64_t>(s) - 1);
    mean += static_cast<long double>(r[static_cast<std::size_t>(std::llabs(d))]) * (aa[i] + bb[i]);
  }
  const auto k = static_cast<long double>(segments);
  long double sum = k * moments(0);
  for (std::int64_t j = 1; j < segments; ++j) sum += 2.0L * (k - j) * moments(j * half);
  const long double variance = sum / (k * k);
  return {static_cast<double>(mean), variance > 0.0L ? static_cast<double>(2.0L * mean * mean / variance) : 0.0};
}

// Mean and EDF of each band of the Welch PSD (record_views.cc PsdView) under the autocovariance r
// (at least segment lags).
void PsdTheory(const ViewLayout& layout, const std::vector<double>& r, GaussianViewTheory* t) {
  const std::int64_t seg = layout.psd_segment;
  if (seg <= 0) return;
  const auto s = static_cast<std::size_t>(seg);
  std::vector<double> window(s);
  double w2 = 0.0;
  for (std::size_t k = 0; k < s; ++k) {
    window[k] = 0.5 - 0.5 * std::cos(2.0 * M_PI * static_cast<double>(k) / static_cast<double>(s));
    w2 += window[k] * window[k];
  }
  // Bins >= 2 (the segment mean does not reach them: Hann's transform is zero there):
  // E|X_b|^2 = sum_{|l|<S} R(|l|) rho_w(l) e^{-i 2 pi b l / S}, one real FFT of the lags folded
  // modulo S.
  const std::vector<double> window_correlation = CrossCorrelation(window, window);
  const std::vector<double> rho_w(window_correlation.begin() + static_cast<std::ptrdiff_t>(s - 1), window_correlation.end());
  sim::FftBuffer buffer(s + 2);
  buffer.data()[0] = r[0] * rho_w[0];
  for (std::size_t l = 1; l < s; ++l) buffer.data()[l] = r[l] * rho_w[l] + r[s - l] * rho_w[s - l];
  sim::ForwardRealFft(s, buffer.data());
  std::vector<double> bin_mean(s / 2 + 1);
  for (std::size_t b = 0; b <= s / 2; ++b) bin_mean[b] = buffer.complex_data()[b].real();
  const std::int64_t segments = (layout.num_samples - seg) / (seg / 2) + 1;
  const auto [first_bin_mean, first_bin_edf] = FirstBinMeanAndEdf(window, r, segments);
  bin_mean[1] = first_bin_mean;
  const double k = static_cast<double>(segments);
  const double f_seg = 1.0 + 2.0 * (1.0 / 36.0) * (k - 1.0) / k;
  const double scale = 2.0 * layout.sample_clock.period_s() / w2;
  for (const auto& [b0, b1] : layout.psd_bands) {
    const double bins = static_cast<double>(b1 - b0);
    double sum = 0.0;
    for (int b = b0; b < b1; ++b) sum += bin_mean[static_cast<std::size_t>(b)];
    const double f_bin = 1.0 + 2.0 * (4.0 / 9.0) * (bins - 1.0) / bins + 2.0 * (1.0 / 36.0) * std::max(0.0, bins - 2.0) / bins;
    t->psd_mean.push_back(scale * sum / bins);
    t->psd_edf.push_back(b0 == 1 && b1 == 2 ? first_bin_edf : 2.0 * k * bins / (f_seg * f_bin));
  }
}

// A sum of independent uniform errors has excess kurtosis down to -1.2 (one error alone), and a
// statistic whose variance is the share s error keeps at most s^2 of it (cumulants add).
constexpr double kUniformExcessKurtosis = 1.2;
// The fine quantizer's bound: its kurtosis shift at most a tenth of the kurtosis view's standard
// deviation, sqrt(24 / N), on N samples.
constexpr double kFineQuantizerKurtosisSds = 0.1;

}  // namespace

double QuantizerShareOfDifferences(const sim::SensorModel& model) {
  if (!model.angle_quantizer && !model.rate_quantizer) return 0.0;
  sim::SensorModel signal = model;
  signal.angle_quantizer.reset();
  signal.rate_quantizer.reset();
  const std::vector<double> r = model.GaussianAutocovariance(2);
  const std::vector<double> r_signal = signal.GaussianAutocovariance(2);
  const double total = 2.0 * (r[0] - r[1]);
  const double error = total - 2.0 * (r_signal[0] - r_signal[1]);
  if (!(total > 0.0)) return 1.0;
  return std::clamp(error / total, 0.0, 1.0);
}

bool IsGaussianModel(const sim::SensorModel& model, std::int64_t num_samples) {
  if (model.angle_quantizer || model.rate_quantizer) {
    const double share = QuantizerShareOfDifferences(model);
    const double kurtosis_sd = std::sqrt(24.0 / static_cast<double>(std::max<std::int64_t>(num_samples, 1)));
    if (!(kUniformExcessKurtosis * share * share <= kFineQuantizerKurtosisSds * kurtosis_sd)) return false;
  }
  for (const sim::NoiseTerm& term : model.terms) {
    const bool gaussian = std::visit(
        [](const auto& t) {
          using T = std::decay_t<decltype(t)>;
          return std::is_same_v<T, sim::QuantizationNoise> || std::is_same_v<T, sim::WhiteRateNoise> ||
                 std::is_same_v<T, sim::FlickerNoise> || std::is_same_v<T, sim::FlickerGaussMarkovSum> ||
                 std::is_same_v<T, sim::RandomWalkRate> || std::is_same_v<T, sim::RateRamp> ||
                 std::is_same_v<T, sim::GaussMarkov> || std::is_same_v<T, sim::Resonance>;
        },
        term);
    if (!gaussian) return false;
  }
  return true;
}

namespace {

// The theory of a Gaussian model, with a warm-up drift's share added when `drift` is given
// (then `model` is the Gaussian part).
GaussianViewTheory GaussianTheory(const sim::SensorModel& model, const ViewLayout& layout, const WarmupDriftPath* drift) {
  const std::int64_t n = layout.num_samples;
  // Every lag a view reads is at most N (OHVAR: (T - 1) + 3m = N; the increments:
  // (blocks - 1) m + m <= N; the halves, windows and PSD segments are shorter).
  const std::vector<double> r = model.GaussianAutocovariance(n + 1);
  const std::vector<long double> variogram = estimators::PhaseVariogram(r, n + 1);
  GaussianViewTheory t;
  // The split variogram: the same bits as the long doubles, about twice as fast (exact_avar_variance.h).
  const estimators::SplitVariogram split = estimators::SplitPhaseVariogram(variogram);
  const sim::RecordShape half{n / 2, sim::AvarEstimatorKind::kOverlapping};
  const sim::RecordShape window{n / kDynamicWindows, sim::AvarEstimatorKind::kOverlapping};
  // Every (view, m) is an independent O(N) sum into its own slot: spread over the threads when
  // the caller runs none (the same bits for any thread count), each thread's scratch reused for
  // all its sums.
  const auto hadamard_count = static_cast<std::int64_t>(layout.hadamard_m.size());
  const auto halves_count = static_cast<std::int64_t>(layout.halves_m.size());
  const auto dynamic_count = static_cast<std::int64_t>(layout.dynamic_m.size());
  const std::int64_t sums = hadamard_count + halves_count + dynamic_count;
  std::vector<estimators::AvarMoments> moments(static_cast<std::size_t>(sums));
#pragma omp parallel if (sums > 1)
  {
    estimators::MomentScratch scratch;
#pragma omp for schedule(dynamic, 1)
    for (std::int64_t i = 0; i < sums; ++i) {
      const auto at = static_cast<std::size_t>(i);
      if (i < hadamard_count) {
        moments[at] = estimators::ExactOhvarMomentsFromVariogram(variogram, split, layout.hadamard_m[at], n, &scratch);
      } else if (i < hadamard_count + halves_count) {
        moments[at] = estimators::ExactAvarMomentsFromVariogram(
            variogram, split, layout.halves_m[static_cast<std::size_t>(i - hadamard_count)], half, &scratch);
      } else {
        moments[at] = estimators::ExactAvarMomentsFromVariogram(
            variogram, split, layout.dynamic_m[static_cast<std::size_t>(i - hadamard_count - halves_count)], window,
            &scratch);
      }
    }
  }
  for (std::int64_t i = 0; i < hadamard_count; ++i) {
    const estimators::AvarMoments& h = moments[static_cast<std::size_t>(i)];
    if (!(h.mean > 0.0) || !(h.variance > 0.0)) return {};
    t.hadamard_mean.push_back(h.mean);
    t.hadamard_edf.push_back(h.edf());
  }
  for (std::int64_t m : layout.kurtosis_m) t.kurtosis_effective_count.push_back(KurtosisEffectiveCount(variogram, m, n));
  for (std::int64_t i = 0; i < halves_count; ++i) {
    t.halves_edf.push_back(moments[static_cast<std::size_t>(hadamard_count + i)].edf());
  }
  for (std::int64_t i = 0; i < dynamic_count; ++i) {
    t.dynamic_edf.push_back(moments[static_cast<std::size_t>(hadamard_count + halves_count + i)].edf());
  }
  PsdTheory(layout, r, &t);
  if (drift != nullptr) {
    GaussianPartMoments parts;
    parts.hadamard.assign(moments.begin(), moments.begin() + hadamard_count);
    parts.halves.assign(moments.begin() + hadamard_count, moments.begin() + hadamard_count + halves_count);
    parts.dynamic.assign(moments.begin() + hadamard_count + halves_count, moments.end());
    AddWarmupDrift(*drift, layout, variogram, parts, &t);
  }
  return t;
}

}  // namespace

GaussianViewTheory ExactGaussianViews(const sim::SensorModel& model, const ViewLayout& layout) {
  std::optional<WarmupDriftPath> drift;
  sim::SensorModel gaussian_part;
  if (!IsGaussianModel(model, layout.num_samples)) {
    drift = SplitWarmupDrift(model, layout.num_samples, &gaussian_part);
    if (!drift) return {};
  }
  return GaussianTheory(drift ? gaussian_part : model, layout, drift ? &*drift : nullptr);
}

double GaussianViewZ(View view, const GaussianViewTheory& t, double observed, std::size_t i, double* expected) {
  switch (view) {
    case View::kHadamard:
    case View::kPsd: {
      const double mean = view == View::kHadamard ? t.hadamard_mean[i] : t.psd_mean[i];
      const double edf = view == View::kHadamard ? t.hadamard_edf[i] : t.psd_edf[i];
      *expected = mean;
      return ZFromChiSquare(std::exp(observed), mean, edf);
    }
    case View::kKurtosis: {
      const double n_eff = t.kurtosis_effective_count[i];
      const double gaussian_mean = -6.0 / (n_eff + 1.0);
      const double shift = t.kurtosis_shift.empty() ? 0.0 : t.kurtosis_shift[i];
      const double ratio = t.kurtosis_sd_ratio.empty() ? 1.0 : t.kurtosis_sd_ratio[i];
      *expected = gaussian_mean + shift;
      // The drift's shift and spread applied about the Gaussian law (warmup_drift_views.h).
      return ZFromKurtosis(gaussian_mean + (observed - gaussian_mean - shift) / ratio, n_eff);
    }
    case View::kHalves: {
      const double offset = t.halves_log_offset.empty() ? 0.0 : t.halves_log_offset[i];
      *expected = offset;
      return ZFromLogRatio(observed - offset, t.halves_edf[i],
                           t.halves_edf_second.empty() ? t.halves_edf[i] : t.halves_edf_second[i]);
    }
    case View::kDynamic: {
      if (t.dynamic_log_means.empty() || t.dynamic_log_means[i].empty()) {
        // The typical range, 2.847 sd of ln(chi2_nu / nu) (8 normal values).
        const double edf = t.dynamic_edf[i];
        *expected = edf > 0.0 ? 2.847 * std::sqrt(boost::math::trigamma(0.5 * edf)) : kNaN;
        return ZFromLogRange(observed, edf, kDynamicWindows);
      }
      const std::vector<double>& log_means = t.dynamic_log_means[i];
      const std::vector<double>& edfs = t.dynamic_edfs[i];
      // The windows' spread of means plus the typical range of the narrowest law.
      const auto [lo, hi] = std::minmax_element(log_means.begin(), log_means.end());
      *expected = *hi - *lo + 2.847 * std::sqrt(boost::math::trigamma(0.5 * *std::min_element(edfs.begin(), edfs.end())));
      return ZFromLogRangeOfUnequal(observed, log_means, edfs);
    }
    default:
      *expected = kNaN;
      return kNaN;
  }
}

}  // namespace allanlab::experiments
