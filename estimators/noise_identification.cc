#include "estimators/noise_identification.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

namespace allanlab::estimators {
namespace {

// Riley & Greenhall (2004): the lag-1 ACF is trustworthy from about 30 points on; below that
// SP 1065 §5.6 falls back on the B1 ratio, which needs three points (with two the sample and
// the Allan variance coincide and the ratio is 1 whatever the noise).
constexpr std::size_t kMinAcfPoints = 30;
constexpr std::size_t kMinB1Points = 3;
// Differencing stops at d_max = 2 (the Allan variance's own order): rate input reaches alpha
// = -4 - 2 delta that way, far enough to clamp anything steeper to -2.
constexpr int kMaxDifferences = 2;
// delta = r1 / (1 + r1) >= 0.25 means the series is still too correlated (alpha < -0.5 at the
// current order) and one more difference is needed.
constexpr double kDeltaLimit = 0.25;
// R(n) separates white phase, flicker phase and white FM only from m = 4 on (0.25, 0.39, 0.5;
// at m = 2 they are 0.50, 0.52, 0.5).
constexpr std::int64_t kMinRnFactor = 4;

// Non-overlapping m-averages of the mean-removed record: the mean goes first so that a large
// bias costs no digits in the differences below.
std::vector<double> ClusterMeans(std::span<const double> rate, std::int64_t m) {
  long double mean = 0.0L;
  for (double v : rate) mean += v;
  mean /= static_cast<long double>(rate.size());
  const std::size_t count = rate.size() / static_cast<std::size_t>(m);
  std::vector<double> means(count);
  for (std::size_t k = 0; k < count; ++k) {
    long double sum = 0.0L;
    for (std::int64_t i = 0; i < m; ++i) sum += rate[k * m + i] - mean;
    means[k] = static_cast<double>(sum / m);
  }
  return means;
}

// A rate ramp would read as random walk; Riley & Greenhall remove it before identifying.
void RemoveLinearTrend(std::vector<double>& x) {
  const double n = static_cast<double>(x.size());
  const double t_mean = 0.5 * (n - 1.0);
  long double x_mean = 0.0L, stt = 0.0L, sxt = 0.0L;
  for (double v : x) x_mean += v;
  x_mean /= n;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const double t = i - t_mean;
    stt += t * t;
    sxt += t * (x[i] - x_mean);
  }
  const double slope = stt > 0.0L ? static_cast<double>(sxt / stt) : 0.0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    x[i] -= static_cast<double>(x_mean) + slope * (i - t_mean);
  }
}

// Riley & Greenhall (2004) eq. 2 (biased estimator: sums over N - 1 and N terms).
double Lag1Autocorrelation(const std::vector<double>& x) {
  long double mean = 0.0L;
  for (double v : x) mean += v;
  mean /= static_cast<long double>(x.size());
  long double num = 0.0L, den = 0.0L;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const long double c = x[i] - mean;
    den += c * c;
    if (i + 1 < x.size()) num += c * (x[i + 1] - mean);
  }
  return den > 0.0L ? static_cast<double>(num / den) : 0.0;
}

int ClampAlpha(double alpha) { return static_cast<int>(std::clamp(std::lround(alpha), -2L, 2L)); }

// For S ~ f^p (p > -1 after d differences) the lag-1 ACF tends to r1 = -p/2 / (1 + p/2), so
// delta = r1 / (1 + r1) = -p/2 and p = -2 delta; each difference of rate raised p by 2, so the
// rate exponent is alpha = -2 (delta + d). (Phase input would add 2; rate is frequency here.)
int AcfAlpha(std::vector<double> x) {
  for (int d = 0;; ++d) {
    const double r1 = Lag1Autocorrelation(x);
    // r1 -> -1 is an alternating series, white phase or bluer: alpha at the top of the range.
    const double delta = r1 > -1.0 + 1e-12 ? r1 / (1.0 + r1) : -1e9;
    if (delta < kDeltaLimit || d >= kMaxDifferences) return ClampAlpha(-2.0 * (delta + d));
    for (std::size_t i = 0; i + 1 < x.size(); ++i) x[i] = x[i + 1] - x[i];
    x.pop_back();
  }
}

// Barnes' bias function B1(N, mu) = E[sample variance of N averages] / AVAR for AVAR ~ tau^mu
// (SP 1065 eq. 66; the mu = 0 entry is the limit N ln N / (2 (N - 1) ln 2)).
double B1Theory(double n, int mu) {
  if (mu == 0) return n * std::log(n) / (2.0 * (n - 1.0) * std::numbers::ln2);
  return n * (1.0 - std::pow(n, mu)) / (2.0 * (n - 1.0) * (1.0 - std::pow(2.0, mu)));
}

// MVAR(m) / OAVAR(m). Mod Allan differences are m-averages of consecutive Allan differences, so
// one pass with two running window sums and a ring of the last m Allan differences gives both in
// O(m) memory (this runs on records of any length, at the longest taus).
double ModifiedToAllanRatio(std::span<const double> rate, std::int64_t m) {
  const auto n = static_cast<std::int64_t>(rate.size());
  if (3 * m > n) return 0.0;
  long double mean = 0.0L;
  for (double v : rate) mean += v;
  mean /= n;
  auto y = [&](std::int64_t i) { return static_cast<long double>(rate[i]) - mean; };
  long double first = 0.0L, second = 0.0L;  // sums over [t, t+m) and [t+m, t+2m)
  for (std::int64_t i = 0; i < m; ++i) {
    first += y(i);
    second += y(i + m);
  }
  std::vector<long double> ring(static_cast<std::size_t>(m), 0.0L);
  long double window = 0.0L, avar = 0.0L, mvar = 0.0L;
  const std::int64_t count = n - 2 * m + 1;  // Allan differences (times m)
  for (std::int64_t t = 0; t < count; ++t) {
    const long double a = second - first;
    avar += a * a;
    long double& slot = ring[static_cast<std::size_t>(t % m)];
    window += a - slot;
    slot = a;
    if (t >= m - 1) mvar += (window / m) * (window / m);
    if (t + 1 < count) {
      first += y(t + m) - y(t);
      second += y(t + 2 * m) - y(t + m);
    }
  }
  avar /= count;
  mvar /= count - m + 1;
  return avar > 0.0L ? static_cast<double>(mvar / avar) : 0.0;
}

// SP 1065 §5.6: R(n) = MVAR/AVAR is 1/m for white phase, 3 ln(256/27) / (2 (1.038 + 3 ln(pi m)))
// for flicker phase (with the usual f_h = 1/(2 tau0)) and 1/2 for white FM; boundaries are
// geometric means. White FM is among the candidates because B1 from a handful of averages
// often falls below its mu = -1 band while R(n), from the whole record, is far more precise.
int PhaseNoiseOrWhiteFm(std::span<const double> rate, std::int64_t m) {
  if (m < kMinRnFactor) return 2;
  const double md = static_cast<double>(m);
  const double white_phase = 1.0 / md;
  const double flicker_phase =
      3.0 * std::log(256.0 / 27.0) / (2.0 * (1.038 + 3.0 * std::log(std::numbers::pi * md)));
  const double white_fm = 0.5;
  const double rn = ModifiedToAllanRatio(rate, m);
  if (rn < std::sqrt(white_phase * flicker_phase)) return 2;
  return rn < std::sqrt(flicker_phase * white_fm) ? 1 : 0;
}

NoiseId B1Identification(std::span<const double> rate, std::int64_t m,
                         const std::vector<double>& means) {
  const double n = static_cast<double>(means.size());
  long double mean = 0.0L;
  for (double v : means) mean += v;
  mean /= n;
  long double var = 0.0L, avar = 0.0L;
  for (std::size_t k = 0; k < means.size(); ++k) {
    var += (means[k] - mean) * (means[k] - mean);
    if (k + 1 < means.size()) avar += (means[k + 1] - means[k]) * (means[k + 1] - means[k]);
  }
  var /= n - 1.0;
  avar /= 2.0 * (n - 1.0);
  if (!(avar > 0.0L)) return {};
  const double b1 = static_cast<double>(var / avar);
  // AVAR ~ tau^mu: mu = 1, 0, -1 are RWFM, FFM, WFM (alpha = -mu - 1); mu = -2 is white or
  // flicker phase, which R(n) tells apart. Boundaries: geometric means of neighbouring
  // expectations.
  NoiseId id{0, true, true};
  for (int mu = 1; mu >= -1; --mu) {
    if (b1 > std::sqrt(B1Theory(n, mu) * B1Theory(n, mu - 1))) {
      id.alpha = -mu - 1;
      return id;
    }
  }
  id.alpha = PhaseNoiseOrWhiteFm(rate, m);
  return id;
}


// Identification from the m-averages (any constant offset: the trend removal, the ACF and the
// B1 ratio do not see it).
NoiseId IdentifyFromMeans(std::span<const double> rate, std::int64_t m, std::vector<double> means) {
  if (means.size() >= kMinAcfPoints) {
    RemoveLinearTrend(means);
    return {AcfAlpha(std::move(means)), true, false};
  }
  if (means.size() >= kMinB1Points) return B1Identification(rate, m, means);
  return {};
}

}  // namespace

NoiseId IdentifyNoise(std::span<const double> rate, std::int64_t m) {
  if (m < 1 || rate.size() < static_cast<std::size_t>(m)) return {};
  return IdentifyFromMeans(rate, m, ClusterMeans(rate, m));
}

NoiseId IdentifyNoise(std::span<const double> rate, std::span<const double> phase, std::int64_t m) {
  if (m < 1 || rate.size() < static_cast<std::size_t>(m) || phase.size() != rate.size() + 1) {
    return IdentifyNoise(rate, m);
  }
  const std::size_t count = rate.size() / static_cast<std::size_t>(m);
  const auto mu = static_cast<std::size_t>(m);
  auto mean_at = [&](std::size_t k) { return (phase[(k + 1) * mu] - phase[k * mu]) / m; };
  if (count < kMinAcfPoints) {
    std::vector<double> means(count);
    for (std::size_t k = 0; k < count; ++k) means[k] = mean_at(k);
    return IdentifyFromMeans(rate, m, std::move(means));
  }
  // The lag-1 ACF method without storing the m-averages (at m = 1 they would be a second copy of
  // the record): each differencing order is evaluated on the fly, in two passes (mean, then
  // products), from the same arithmetic as the stored version: the detrended averages at d = 0;
  // their differences at d >= 1, where the trend's slope is a constant the ACF's own mean
  // removal takes away.
  const double n = static_cast<double>(count);
  const double t_mean = 0.5 * (n - 1.0);
  long double x_mean = 0.0L, stt = 0.0L, sxt = 0.0L;
  for (std::size_t i = 0; i < count; ++i) x_mean += mean_at(i);
  x_mean /= n;
  for (std::size_t i = 0; i < count; ++i) {
    const double t = i - t_mean;
    stt += t * t;
    sxt += t * (mean_at(i) - x_mean);
  }
  const double slope = stt > 0.0L ? static_cast<double>(sxt / stt) : 0.0;
  auto series = [&](int d, std::size_t k) -> double {
    if (d == 0) return mean_at(k) - (static_cast<double>(x_mean) + slope * (k - t_mean));
    if (d == 1) return mean_at(k + 1) - mean_at(k);
    return mean_at(k + 2) - 2.0 * mean_at(k + 1) + mean_at(k);
  };
  for (int d = 0;; ++d) {
    const std::size_t len = count - static_cast<std::size_t>(d);
    long double mean = 0.0L;
    for (std::size_t i = 0; i < len; ++i) mean += series(d, i);
    mean /= static_cast<long double>(len);
    long double num = 0.0L, den = 0.0L;
    long double c = series(d, 0) - mean;
    for (std::size_t i = 0; i < len; ++i) {
      den += c * c;
      if (i + 1 < len) {
        const long double next = series(d, i + 1) - mean;
        num += c * next;
        c = next;
      }
    }
    const double r1 = den > 0.0L ? static_cast<double>(num / den) : 0.0;
    const double delta = r1 > -1.0 + 1e-12 ? r1 / (1.0 + r1) : -1e9;
    if (delta < kDeltaLimit || d >= kMaxDifferences) return {ClampAlpha(-2.0 * (delta + d)), true, false};
  }
}

}  // namespace allanlab::estimators
