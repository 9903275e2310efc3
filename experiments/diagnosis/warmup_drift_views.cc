#include "experiments/diagnosis/warmup_drift_views.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <map>
#include <tuple>
#include <type_traits>
#include <variant>

#include <boost/math/special_functions/trigamma.hpp>

#include "experiments/diagnosis/welch_psd.h"
#include "sim/band_limit.h"

namespace allanlab::experiments {
namespace {

// Below this share of the Gaussian mean the drift's own value leaves the statistic's law alone:
// the cross term's variance is then at most about twice that share of the Gaussian variance.
constexpr double kNegligibleShare = 1e-5;

// (-1)^j binom(2n, n + j), j = 0 .. n: the autocorrelation of the n-th difference's coefficients.
std::vector<long double> DifferenceAutocorrelation(int order) {
  std::vector<long double> a;
  for (int j = 0; j <= order; ++j) {
    long double binomial = 1.0L;  // binom(2n, n + j)
    for (int k = 1; k <= order - j; ++k) binomial = binomial * (order + j + k) / k;
    a.push_back((j % 2 == 0 ? 1.0L : -1.0L) * binomial);
  }
  return a;
}

// s0 = sum_{i<T} rho^{2i} = (1 - rho^{2T}) / (1 - rho^2), rho = e^{-lambda}: the drift's own
// value and the cross sum's lag-0 term both carry it.
long double SquaredPathSum(long double lambda, std::int64_t t) {
  return -std::expm1(-2.0L * lambda * static_cast<long double>(t)) / -std::expm1(-2.0L * lambda);
}

}  // namespace

KurtosisMoments ShiftedKurtosis(std::span<const double> u) {
  const double n = static_cast<double>(u.size());
  double v = 0.0, mu4 = 0.0, var_m2 = 0.0, var_m4 = 0.0, cov = 0.0;
  for (double p : u) {
    const double p2 = p * p, p4 = p2 * p2, p6 = p4 * p2, p8 = p4 * p4;
    const double e2 = p2 + 1.0, e4 = p4 + 6.0 * p2 + 3.0, e6 = p6 + 15.0 * p4 + 45.0 * p2 + 15.0;
    const double e8 = p8 + 28.0 * p6 + 210.0 * p4 + 420.0 * p2 + 105.0;
    v += p2;
    mu4 += p4;
    var_m2 += e4 - e2 * e2;
    var_m4 += e8 - e4 * e4;
    cov += e6 - e4 * e2;
  }
  v /= n;
  mu4 /= n;
  var_m2 /= n * n;
  var_m4 /= n * n;
  cov /= n * n;
  const double m2 = 1.0 + v, m4 = 3.0 + 6.0 * v + mu4;
  KurtosisMoments k;
  k.shift = m4 / (m2 * m2) - 3.0;
  k.variance = var_m4 / std::pow(m2, 4) - 4.0 * m4 * cov / std::pow(m2, 5) + 4.0 * m4 * m4 * var_m2 / std::pow(m2, 6);
  return k;
}

std::optional<WarmupDriftPath> SplitWarmupDrift(const sim::SensorModel& model, std::int64_t num_samples,
                                                sim::SensorModel* gaussian_part) {
  const sim::ExponentialDrift* drift = nullptr;
  sim::SensorModel rest = model;
  rest.terms.clear();
  for (const sim::NoiseTerm& term : model.terms) {
    if (const auto* d = std::get_if<sim::ExponentialDrift>(&term)) {
      if (drift != nullptr) return std::nullopt;
      drift = d;
    } else {
      rest.terms.push_back(term);
    }
  }
  if (drift == nullptr || !IsGaussianModel(rest, num_samples)) return std::nullopt;
  const double tau0 = model.sample_clock.period_s();
  WarmupDriftPath path;
  path.decay_per_sample = tau0 / drift->time_constant_s;
  path.output_amplitude_rad_per_s =
      model.band_limit.enabled()
          ? drift->OutputAmplitude(tau0, sim::SharedBandLimitChain(model.band_limit, model.sample_clock.rate_hz())->held_response())
          : drift->OutputAmplitude(tau0);
  *gaussian_part = std::move(rest);
  return path;
}

long double DriftCrossSum(std::span<const long double> variogram, int order, std::int64_t m,
                          std::int64_t differences, double decay_per_sample, std::int64_t keep_up_to) {
  const std::int64_t t = differences;
  const long double lambda = decay_per_sample;
  const long double one_minus_rho2 = -std::expm1(-2.0L * lambda);
  const long double s0 = SquaredPathSum(lambda, t);
  // sum_{|h|<T} C(h) rho^|h| (1 - rho^{2(T-|h|)}) / (1 - rho^2) as C(0) s0 + 2 (A - B) / (1 - rho^2),
  // A = sum_{h>=1} C(h) rho^h (rho^h ascending), B = sum_{h>=1} C(h) rho^{2T-h} (descending from
  // rho^{T+1}), so no power is formed by division.
  const std::vector<long double> a = DifferenceAutocorrelation(order);
  auto c = [&](std::int64_t h) {
    long double sum = a[0] * variogram[static_cast<std::size_t>(h)];
    for (int j = 1; j <= order; ++j) {
      sum += a[static_cast<std::size_t>(j)] * (variogram[static_cast<std::size_t>(std::llabs(h + j * m))] +
                                               variogram[static_cast<std::size_t>(std::llabs(h - j * m))]);
    }
    return -0.5L * sum;
  };
  // C(h) formed once and kept for both passes up to keep_up_to (header); beyond, formed in each
  // pass. The same values either way.
  // kept[h - 1] = C(h), appended rather than sized first (no 16 MB of zeros to write).
  std::vector<long double> kept;
  if (t <= keep_up_to) {
    kept.reserve(static_cast<std::size_t>(std::max<std::int64_t>(t - 1, 0)));
    for (std::int64_t h = 1; h < t; ++h) kept.push_back(c(h));
  }
  auto c_at = [&](std::int64_t h) { return kept.empty() ? c(h) : kept[static_cast<std::size_t>(h - 1)]; };
  const long double rho = std::exp(-lambda);
  long double ascending = 0.0L, power = 1.0L;
  for (std::int64_t h = 1; h < t; ++h) {
    power *= rho;
    ascending += c_at(h) * power;
  }
  long double descending = 0.0L;
  power = std::exp(-lambda * static_cast<long double>(t + 1));
  for (std::int64_t h = t - 1; h >= 1; --h) {
    descending += c_at(h) * power;
    power *= rho;
  }
  return c(0) * s0 + 2.0L * (ascending - descending) / one_minus_rho2;
}

DriftShift DriftShiftFromCrossSum(const long double* cross_sum, int order, std::int64_t m, std::int64_t differences,
                                  double amplitude_rad_per_s, double decay_per_sample) {
  DriftShift s;
  const std::int64_t t = differences;
  if (t < 1 || amplitude_rad_per_s == 0.0) return s;
  const long double lambda = decay_per_sample;
  const long double one_minus_rho = -std::expm1(-lambda);
  const long double one_minus_rho_m = -std::expm1(-lambda * static_cast<long double>(m));
  const long double d = static_cast<long double>(amplitude_rad_per_s) * std::pow(one_minus_rho_m, order) / one_minus_rho;
  const long double s0 = SquaredPathSum(lambda, t);
  const long double k = (order == 2 ? 2.0L : 6.0L) * static_cast<long double>(m) * static_cast<long double>(m);
  s.own = static_cast<double>(d * d * s0 / (k * static_cast<long double>(t)));
  if (cross_sum == nullptr) return s;
  const long double scale = 2.0L * d / (k * static_cast<long double>(t));
  s.cross_variance = static_cast<double>(std::max(0.0L, scale * scale * *cross_sum));
  return s;
}

DriftShift QuadraticStatisticShift(std::span<const long double> variogram, int order, std::int64_t m,
                                   std::int64_t differences, double amplitude_rad_per_s, double decay_per_sample) {
  if (variogram.empty() || differences < 1 || amplitude_rad_per_s == 0.0) {
    return DriftShiftFromCrossSum(nullptr, order, m, differences, amplitude_rad_per_s, decay_per_sample);
  }
  const long double cross_sum = DriftCrossSum(variogram, order, m, differences, decay_per_sample);
  return DriftShiftFromCrossSum(&cross_sum, order, m, differences, amplitude_rad_per_s, decay_per_sample);
}

void AddWarmupDrift(const WarmupDriftPath& drift, const ViewLayout& layout, std::span<const long double> variogram,
                    const GaussianPartMoments& moments, GaussianViewTheory* t) {
  const std::int64_t n = layout.num_samples;
  const double a = drift.output_amplitude_rad_per_s, lambda = drift.decay_per_sample;
  auto amplitude_at = [&](std::int64_t first) { return a * std::exp(-lambda * static_cast<double>(first)); };
  std::map<std::tuple<int, std::int64_t, std::int64_t>, long double> cross_sums;
  // One segment's statistic: the Gaussian part's moments plus the drift's (its own value and the
  // cross term's variance, skipped where the own value is negligible).
  auto shifted = [&](const estimators::AvarMoments& g, int order, std::int64_t m, std::int64_t segment,
                     std::int64_t first) {
    estimators::AvarMoments total = g;
    const std::int64_t differences = segment - order * m + 1;
    const DriftShift own = DriftShiftFromCrossSum(nullptr, order, m, differences, amplitude_at(first), lambda);
    if (!(own.own > kNegligibleShare * g.mean)) return total;
    // Segments of one length share the cross sum (the two halves, the dynamic view's windows).
    const auto key = std::make_tuple(order, m, differences);
    auto found = cross_sums.find(key);
    if (found == cross_sums.end()) {
      found = cross_sums.emplace(key, DriftCrossSum(variogram, order, m, differences, lambda)).first;
    }
    const DriftShift s = DriftShiftFromCrossSum(&found->second, order, m, differences, amplitude_at(first), lambda);
    total.mean += s.own;
    total.variance += s.cross_variance;
    return total;
  };
  for (std::size_t i = 0; i < layout.hadamard_m.size(); ++i) {
    const estimators::AvarMoments h = shifted(moments.hadamard[i], 3, layout.hadamard_m[i], n, 0);
    t->hadamard_mean[i] = h.mean;
    t->hadamard_edf[i] = h.edf();
  }
  const std::int64_t half = n / 2;
  for (std::size_t i = 0; i < layout.halves_m.size(); ++i) {
    const estimators::AvarMoments first = shifted(moments.halves[i], 2, layout.halves_m[i], half, 0);
    const estimators::AvarMoments second = shifted(moments.halves[i], 2, layout.halves_m[i], half, half);
    t->halves_edf[i] = first.edf();
    t->halves_edf_second.push_back(second.edf());
    t->halves_log_offset.push_back(std::log(first.mean / second.mean));
  }
  const std::int64_t window = n / kDynamicWindows;
  t->dynamic_log_means.assign(layout.dynamic_m.size(), {});
  t->dynamic_edfs.assign(layout.dynamic_m.size(), {});
  for (std::size_t i = 0; i < layout.dynamic_m.size(); ++i) {
    std::vector<double> log_means, edfs;
    bool alike = true;
    const estimators::AvarMoments& g = moments.dynamic[i];
    for (int w = 0; w < kDynamicWindows; ++w) {
      const estimators::AvarMoments s = shifted(g, 2, layout.dynamic_m[i], window, w * window);
      alike = alike && s.mean == g.mean && s.variance == g.variance;
      log_means.push_back(std::log(s.mean));
      edfs.push_back(s.edf());
    }
    if (alike) continue;
    t->dynamic_log_means[i] = std::move(log_means);
    t->dynamic_edfs[i] = std::move(edfs);
  }
  // The drift on the output samples, for the views that read the samples (PSD, kurtosis).
  std::vector<double> path(static_cast<std::size_t>(n));
  for (std::int64_t k = 0; k < n; ++k) path[static_cast<std::size_t>(k)] = amplitude_at(k);
  if (layout.psd_segment > 0 && !t->psd_mean.empty()) {
    const std::vector<double> density =
        WelchPsd(path, static_cast<std::size_t>(layout.psd_segment), layout.sample_clock.period_s());
    for (std::size_t i = 0; i < layout.psd_bands.size(); ++i) {
      const auto [b0, b1] = layout.psd_bands[i];
      double p = 0.0;
      for (int b = b0; b < b1; ++b) p += density[static_cast<std::size_t>(b)];
      p /= static_cast<double>(b1 - b0);
      const double e = t->psd_mean[i];
      if (!(p > kNegligibleShare * e)) continue;
      t->psd_edf[i] *= (e + p) * (e + p) / (e * e + 2.0 * e * p);
      t->psd_mean[i] = e + p;
    }
  }
  t->kurtosis_shift.assign(layout.kurtosis_m.size(), 0.0);
  t->kurtosis_sd_ratio.assign(layout.kurtosis_m.size(), 1.0);
  for (std::size_t i = 0; i < layout.kurtosis_m.size(); ++i) {
    const std::int64_t m = layout.kurtosis_m[i];
    const std::int64_t blocks = n / m;
    if (blocks < 3) continue;
    const long double var_g = 4.0L * variogram[static_cast<std::size_t>(m)] - variogram[static_cast<std::size_t>(2 * m)];
    if (!(var_g > 0.0L)) continue;
    const double sd_g = std::sqrt(static_cast<double>(var_g));
    // The drift's block sums are geometric: sum_{k<m} a' rho^{b m + k}; their increments, in
    // units of the Gaussian increments' sd, centred.
    const double block_sum = a * -std::expm1(-lambda * static_cast<double>(m)) / -std::expm1(-lambda);
    std::vector<double> u(static_cast<std::size_t>(blocks - 1));
    double mean = 0.0;
    for (std::int64_t b = 0; b + 1 < blocks; ++b) {
      const double step = block_sum * std::exp(-lambda * static_cast<double>(b * m)) * std::expm1(-lambda * static_cast<double>(m));
      u[static_cast<std::size_t>(b)] = step / sd_g;
      mean += u[static_cast<std::size_t>(b)];
    }
    mean /= static_cast<double>(u.size());
    double spread = 0.0;
    for (double& x : u) {
      x -= mean;
      spread = std::max(spread, std::abs(x));
    }
    if (!(spread > 1e-4)) continue;  // below 1e-16 of the fourth moment: the Gaussian law as it is
    const KurtosisMoments with = ShiftedKurtosis(u);
    t->kurtosis_shift[i] = with.shift;
    t->kurtosis_sd_ratio[i] = std::sqrt(with.variance / (24.0 / static_cast<double>(u.size())));
  }
}

}  // namespace allanlab::experiments
