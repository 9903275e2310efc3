#include "estimators/noise_identification.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <utility>
#include <vector>

#include "estimators/difference_kernel.h"  // CompensatedSum
#include "estimators/phase_checkpoints.h"
#include "estimators/ratio_window_steps.h"

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

// body(lo, hi) over [0, count) in blocks of 4096: each block's lane sums go into compensated
// totals, so a 1e8-term sum keeps its digits.
template <typename Body>
void ForBlocks(std::size_t count, Body&& body) {
  constexpr std::size_t kBlock = 4096;
  for (std::size_t lo = 0; lo < count; lo += kBlock) body(lo, std::min(count, lo + kBlock));
}

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

// -2 (delta + d), kept within [-4, 4] (an alternating series gives delta -> -infinity).
double ContinuousAlpha(double delta, int d) { return std::clamp(-2.0 * (delta + d), -4.0, 4.0); }

NoiseId AcfId(double estimate, std::size_t averages) {
  NoiseId id{ClampAlpha(estimate), true, false};
  id.estimate = estimate;
  id.averages = static_cast<std::int64_t>(averages);
  return id;
}

// For S ~ f^p (p > -1 after d differences) the lag-1 ACF tends to r1 = -p/2 / (1 + p/2), so
// delta = r1 / (1 + r1) = -p/2 and p = -2 delta; each difference of rate raised p by 2, so the
// rate exponent is alpha = -2 (delta + d). (Phase input would add 2; rate is frequency here.)
// Returns the unrounded exponent.
double AcfAlpha(std::vector<double> x) {
  for (int d = 0;; ++d) {
    const double r1 = Lag1Autocorrelation(x);
    // r1 -> -1 is an alternating series, white phase or bluer: alpha at the top of the range.
    const double delta = r1 > -1.0 + 1e-12 ? r1 / (1.0 + r1) : -1e9;
    if (delta < kDeltaLimit || d >= kMaxDifferences) return ContinuousAlpha(delta, d);
    for (std::size_t i = 0; i + 1 < x.size(); ++i) x[i] = x[i + 1] - x[i];
    x.pop_back();
  }
}

// Barnes' bias function B1(N, mu) = E[sample variance of N averages] / AVAR for AVAR ~ tau^mu
// (SP 1065 eq. 66; the mu = 0 entry is the limit N ln N / (2 (N - 1) ln 2)).
double B1Theory(double n, double mu) {
  if (std::abs(mu) < 1e-9) return n * std::log(n) / (2.0 * (n - 1.0) * std::numbers::ln2);
  return n * (1.0 - std::pow(n, mu)) / (2.0 * (n - 1.0) * (1.0 - std::pow(2.0, mu)));
}

// The mu in [-2, 2] whose B1Theory(n, mu) is b1 (B1 grows with mu), by bisection; the ends
// when b1 lies beyond them.
double B1Exponent(double n, double b1) {
  double lo = -2.0, hi = 2.0;
  if (b1 <= B1Theory(n, -2)) return lo;
  if (b1 >= B1Theory(n, 2)) return hi;
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (lo + hi);
    (B1Theory(n, mid) < b1 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
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
// The same ratio from the integrated record (phase.size() = N + 1, any reference level): the
// Allan differences are second differences of the phase and the window of the last m of them is
// carried along, so no ring is kept and everything is double. Four windows advance per step
// from one carried sum (w_{t+j} = w_t + partial sums of the changes), which keeps the
// loop-carried chain at one addition per four terms; its rounding drifts like a random walk,
// ~sqrt(N) ulp, far below the resolution the boundaries below need.
//
// stretch(slot, lo, count) gives x_lo .. x_{lo + count - 1} (count <= kFlush + 4), valid until
// the next call with the same slot (0..3): the stored record, or stretches rebuilt from its
// checkpoints; the terms are computed from the same x bits either way.
constexpr std::int64_t kRatioFlush = 4096;

template <typename Stretch>
double ModifiedToAllanRatioOfStretches(std::int64_t n, std::int64_t m, Stretch&& stretch) {
  if (3 * m > n) return 0.0;
  const std::int64_t count = n - 2 * m + 1;  // Allan differences (times m)
  CompensatedSum avar_total, mvar_total;
  // The first window, a_0..a_{m-1}, and their squares.
  double window = 0.0;
  {
    double squares = 0.0;
    for (std::int64_t j0 = 0; j0 < m; j0 += kRatioFlush) {
      const std::int64_t len = std::min(kRatioFlush, m - j0);
      const double* x0 = stretch(0, j0, len);
      const double* x1 = stretch(1, j0 + m, len);
      const double* x2 = stretch(2, j0 + 2 * m, len);
      for (std::int64_t i = 0; i < len; ++i) {
        const double v = (x2[i] - x1[i]) - (x1[i] - x0[i]);
        window += v;
        squares += v * v;
      }
    }
    avar_total.Add(squares);
  }
  // w_t = sum_{j=t-m+1}^{t} a_j for t = m - 1 .. count - 1; w_{t+1} = w_t + a_{t+1} - a_{t+1-m},
  // and the incoming a_{t+1} are the remaining Allan terms.
  const std::int64_t last = count - 1;
  std::int64_t t = m - 1;
  while (t <= last) {
    const std::int64_t end = std::min(last + 1, t + kRatioFlush);
    // This block reads a_u and a_{u-m} for u in [t + 1, min(end, last)]: x at u - m, u, u + m and
    // u + 2m.
    const std::int64_t u0 = t + 1;
    const std::int64_t len = std::min(end, last) - t;
    const double* x0 = len > 0 ? stretch(0, u0 - m, len) : nullptr;
    const double* x1 = len > 0 ? stretch(1, u0, len) : nullptr;
    const double* x2 = len > 0 ? stretch(2, u0 + m, len) : nullptr;
    const double* x3 = len > 0 ? stretch(3, u0 + 2 * m, len) : nullptr;
    // a_u, and a_{u-m}.
    auto lead = [&](std::int64_t u) {
      const std::int64_t i = u - u0;
      return (x3[i] - x2[i]) - (x2[i] - x1[i]);
    };
    auto trail = [&](std::int64_t u) {
      const std::int64_t i = u - u0;
      return (x2[i] - x1[i]) - (x1[i] - x0[i]);
    };
    // Groups of four steps while t + 4 <= min(end, last) (ratio_window_steps.h), then one at a time.
    double s[4] = {0, 0, 0, 0}, q[4] = {0, 0, 0, 0};
    const std::int64_t groups = len > 0 ? len / 4 : 0;
    if (groups > 0) window = RatioWindowSteps(x0, x1, x2, x3, groups, window, s, q);
    t += 4 * groups;
    for (; t < end; ++t) {
      s[0] += window * window;
      if (t < last) {
        const double in = lead(t + 1);
        q[0] += in * in;
        window += in - trail(t + 1);
      }
    }
    mvar_total.Add((s[0] + s[1]) + (s[2] + s[3]));
    avar_total.Add((q[0] + q[1]) + (q[2] + q[3]));
  }
  const double avar = avar_total.Value() / static_cast<double>(count);
  const double md = static_cast<double>(m);
  const double mvar = mvar_total.Value() / (md * md) / static_cast<double>(count - m + 1);
  return avar > 0.0 ? mvar / avar : 0.0;
}

double ModifiedToAllanRatioFromPhase(std::span<const double> phase, std::int64_t m) {
  const double* x = phase.data();
  return ModifiedToAllanRatioOfStretches(static_cast<std::int64_t>(phase.size()) - 1, m,
                                         [x](int, std::int64_t lo, std::int64_t) { return x + lo; });
}

// ratio() gives R(n) of the record at m (from its rate or its integrated record).
int PhaseNoiseOrWhiteFm(const std::function<double()>& ratio, std::int64_t m) {
  if (m < kMinRnFactor) return 2;
  const double md = static_cast<double>(m);
  const double white_phase = 1.0 / md;
  const double flicker_phase =
      3.0 * std::log(256.0 / 27.0) / (2.0 * (1.038 + 3.0 * std::log(std::numbers::pi * md)));
  const double white_fm = 0.5;
  const double rn = ratio();
  if (rn < std::sqrt(white_phase * flicker_phase)) return 2;
  return rn < std::sqrt(flicker_phase * white_fm) ? 1 : 0;
}

NoiseId B1Identification(const std::function<double()>& ratio, std::int64_t m,
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
  id.averages = static_cast<std::int64_t>(means.size());
  for (int mu = 1; mu >= -1; --mu) {
    if (b1 > std::sqrt(B1Theory(n, mu) * B1Theory(n, mu - 1))) {
      id.alpha = -mu - 1;
      id.estimate = -B1Exponent(n, b1) - 1.0;
      return id;
    }
  }
  id.alpha = PhaseNoiseOrWhiteFm(ratio, m);
  id.estimate = id.alpha == 0 ? -B1Exponent(n, b1) - 1.0 : id.alpha;
  return id;
}


// Identification from the m-averages (any constant offset: the trend removal, the ACF and the
// B1 ratio do not see it).
NoiseId IdentifyFromMeans(const std::function<double()>& ratio, std::int64_t m,
                          std::vector<double> means) {
  if (means.size() >= kMinAcfPoints) {
    RemoveLinearTrend(means);
    const std::size_t count = means.size();
    return AcfId(AcfAlpha(std::move(means)), count);
  }
  if (means.size() >= kMinB1Points) return B1Identification(ratio, m, means);
  return {};
}

// Sums of c_k, c_k^2 and c_k c_{k+1} over k < len of a series given by c(k), and its lag-1
// autocorrelation (Riley & Greenhall eq. 2) about the series' own mean.
struct Moments {
  double sum = 0.0, squares = 0.0, products = 0.0, first = 0.0, last = 0.0;
  // The mean e is removed exactly from the moments: sum (c - e)^2 and sum (c_i - e)(c_{i+1} - e).
  double Lag1(std::size_t len) const {
    const double l = static_cast<double>(len);
    const double e = sum / l;
    const double den = squares - l * e * e;
    const double num = products - e * (2.0 * sum - first - last) + (l - 1.0) * e * e;
    return den > 0.0 ? num / den : 0.0;
  }
};

template <typename Series>
Moments LagMoments(std::size_t len, Series&& c) {
  CompensatedSum sum, squares, products;
  ForBlocks(len, [&](std::size_t lo, std::size_t hi) {
    double s[4] = {0, 0, 0, 0}, q[4] = {0, 0, 0, 0}, p[4] = {0, 0, 0, 0};
    double prev = c(lo);
    std::size_t i = lo;
    // Products c_i c_{i+1} for i + 1 < len.
    for (; i + 4 <= hi && i + 4 < len; i += 4) {
      const double c1 = c(i + 1), c2 = c(i + 2), c3 = c(i + 3), c4 = c(i + 4);
      s[0] += prev;
      s[1] += c1;
      s[2] += c2;
      s[3] += c3;
      q[0] += prev * prev;
      q[1] += c1 * c1;
      q[2] += c2 * c2;
      q[3] += c3 * c3;
      p[0] += prev * c1;
      p[1] += c1 * c2;
      p[2] += c2 * c3;
      p[3] += c3 * c4;
      prev = c4;
    }
    for (; i < hi; ++i) {
      s[0] += prev;
      q[0] += prev * prev;
      if (i + 1 < len) {
        const double next = c(i + 1);
        p[0] += prev * next;
        prev = next;
      }
    }
    sum.Add((s[0] + s[1]) + (s[2] + s[3]));
    squares.Add((q[0] + q[1]) + (q[2] + q[3]));
    products.Add((p[0] + p[1]) + (p[2] + p[3]));
  });
  return {sum.Value(), squares.Value(), products.Value(), c(0), c(len - 1)};
}

// The lag-1 ACF identification from m-averages given by mean_at(k), k < count, without storing
// them (at m = 1 they would be a second copy of the record).
template <typename MeanAt>
NoiseId StreamedAcfIdentification(std::size_t count, MeanAt&& mean_at) {
  // One pass for the trend, then one pass per differencing order, each series
  // evaluated on the fly: the detrended averages at d = 0; their differences at d >= 1, where the
  // trend's slope is a constant the ACF's own mean removal takes away. Sums in double lanes
  // flushed into compensated totals (the x87 long double of the stored version cannot be
  // vectorised and cost seconds on 1e8 samples); each series is centred on a level known before
  // its pass (0 for the residuals, the telescoped mean of the differences), and the small
  // remaining mean is removed exactly from the moments.
  const double n = static_cast<double>(count);
  const double t_mean = 0.5 * (n - 1.0);
  CompensatedSum x_sum, xt_sum;
  ForBlocks(count, [&](std::size_t lo, std::size_t hi) {
    double s[4] = {0, 0, 0, 0}, st[4] = {0, 0, 0, 0};
    std::size_t i = lo;
    for (; i + 4 <= hi; i += 4) {
      for (std::size_t l = 0; l < 4; ++l) {
        const double v = mean_at(i + l);
        s[l] += v;
        st[l] += (static_cast<double>(i + l) - t_mean) * v;
      }
    }
    for (; i < hi; ++i) {
      s[0] += mean_at(i);
      st[0] += (static_cast<double>(i) - t_mean) * mean_at(i);
    }
    x_sum.Add((s[0] + s[1]) + (s[2] + s[3]));
    xt_sum.Add((st[0] + st[1]) + (st[2] + st[3]));
  });
  const double x_mean = x_sum.Value() / n;
  // sum (t - t_mean)^2 over t = 0..count-1 = count (count^2 - 1) / 12.
  const double stt = n * (n * n - 1.0) / 12.0;
  const double slope = stt > 0.0 ? xt_sum.Value() / stt : 0.0;
  for (int d = 0;; ++d) {
    const std::size_t len = count - static_cast<std::size_t>(d);
    double level = 0.0;
    if (d == 1) level = (mean_at(count - 1) - mean_at(0)) / static_cast<double>(len);
    if (d == 2) {
      level = ((mean_at(count - 1) - mean_at(count - 2)) - (mean_at(1) - mean_at(0))) /
              static_cast<double>(len);
    }
    Moments moments;
    if (d == 0) {
      moments = LagMoments(len, [&](std::size_t k) {
        return mean_at(k) - (x_mean + slope * (static_cast<double>(k) - t_mean));
      });
    } else if (d == 1) {
      moments = LagMoments(len, [&](std::size_t k) { return (mean_at(k + 1) - mean_at(k)) - level; });
    } else {
      moments = LagMoments(len, [&](std::size_t k) {
        return (mean_at(k + 2) - 2.0 * mean_at(k + 1) + mean_at(k)) - level;
      });
    }
    const double r1 = moments.Lag1(len);
    const double delta = r1 > -1.0 + 1e-12 ? r1 / (1.0 + r1) : -1e9;
    if (delta < kDeltaLimit || d >= kMaxDifferences) return AcfId(ContinuousAlpha(delta, d), count);
  }
}

// Up to this many m-averages (8 MB; identification reads at most 32768 by default) are stored for
// the passes of the ACF identification; more (at m = 1 a second copy of the record) are
// recomputed in every pass. Variable for the test that both give the same bits.
std::size_t max_stored_averages = std::size_t{1} << 20;

// count m-averages from the integrated record sampled every m-th index, x_at(k) = x_{k m}.
template <typename XAt>
NoiseId IdentifyFromSampledPhase(std::size_t count, std::int64_t m, XAt&& x_at,
                                 const std::function<double()>& ratio) {
  auto mean_at = [&](std::size_t k) { return (x_at(k + 1) - x_at(k)) / m; };
  if (count < kMinAcfPoints) {
    std::vector<double> means(count);
    for (std::size_t k = 0; k < count; ++k) means[k] = mean_at(k);
    return IdentifyFromMeans(ratio, m, std::move(means));
  }
  // 1/m is exact for the octave grid's powers of two (at m = 1 the product is the difference
  // itself); elsewhere it is one rounding.
  const double inverse = 1.0 / static_cast<double>(m);
  const auto average = [&](std::size_t k) { return (x_at(k + 1) - x_at(k)) * inverse; };
  if (count > max_stored_averages) return StreamedAcfIdentification(count, average);
  // Few enough to keep: formed once into a buffer kept per thread rather than in each of the two
  // to four passes, which on a long record re-read it at stride m, a cache miss per read; the
  // same values.
  static thread_local std::vector<double> averages;
  if (averages.size() < count) averages.resize(count);
  for (std::size_t k = 0; k < count; ++k) averages[k] = average(k);
  const double* stored = averages.data();
  return StreamedAcfIdentification(count, [stored](std::size_t k) { return stored[k]; });
}

}  // namespace

double ModifiedToAllanRatioOfPhase(std::span<const double> phase, std::int64_t m) {
  return ModifiedToAllanRatioFromPhase(phase, m);
}

double ModifiedToAllanRatioOfCheckpoints(const PhaseCheckpoints& x, std::int64_t first, std::int64_t length,
                                         std::int64_t m) {
  std::vector<double> buffers(4 * static_cast<std::size_t>(kRatioFlush + 4));
  return ModifiedToAllanRatioOfStretches(length, m, [&](int slot, std::int64_t lo, std::int64_t count) {
    const std::span<double> out(buffers.data() + slot * (kRatioFlush + 4), static_cast<std::size_t>(count));
    x.Rebuild(first + lo, out);
    return static_cast<const double*>(out.data());
  });
}

std::size_t SetMaxStoredAveragesForTesting(std::size_t count) { return std::exchange(max_stored_averages, count); }

NoiseId IdentifyNoise(std::span<const double> rate, std::int64_t m) {
  if (m < 1 || rate.size() < static_cast<std::size_t>(m)) return {};
  return IdentifyFromMeans([&] { return ModifiedToAllanRatio(rate, m); }, m, ClusterMeans(rate, m));
}

NoiseId IdentifyNoise(std::span<const double> rate, std::span<const double> phase, std::int64_t m) {
  if (m < 1 || rate.size() < static_cast<std::size_t>(m) || phase.size() != rate.size() + 1) {
    return IdentifyNoise(rate, m);
  }
  const std::size_t count = rate.size() / static_cast<std::size_t>(m);
  const auto mu = static_cast<std::size_t>(m);
  const double* x = phase.data();
  return IdentifyFromSampledPhase(count, m, [x, mu](std::size_t k) { return x[k * mu]; },
                                  [&] { return ModifiedToAllanRatioFromPhase(phase, m); });
}

NoiseId IdentifyNoiseFromSampledPhase(std::span<const double> sampled, std::int64_t m,
                                      const std::function<double()>& modified_to_allan_ratio) {
  if (m < 1 || sampled.size() < 2) return {};
  const double* x = sampled.data();
  return IdentifyFromSampledPhase(sampled.size() - 1, m, [x](std::size_t k) { return x[k]; },
                                  modified_to_allan_ratio);
}

}  // namespace allanlab::estimators
