#include "sim/band_limit.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <numbers>
#include <sstream>

namespace allanlab::sim {
namespace {

// x with sinc(x)^power = 1/sqrt(2), sinc(x) = sin(pi x) / (pi x): the -3 dB point of a box
// (power 1) or of two boxes in cascade (power 2) of unit length, by bisection on (0, 1).
double BoxHalfPowerProduct(int power) {
  double lo = 1e-6, hi = 1.0;
  for (int i = 0; i < 200; ++i) {
    const double x = 0.5 * (lo + hi);
    const double sinc = std::sin(std::numbers::pi * x) / (std::numbers::pi * x);
    (std::pow(sinc, power) > 1.0 / std::numbers::sqrt2 ? lo : hi) = x;
  }
  return 0.5 * (lo + hi);
}

}  // namespace

std::string_view LowPassKindName(LowPassKind kind) {
  switch (kind) {
    case LowPassKind::kNone: return "none";
    case LowPassKind::kFirstOrder: return "first_order";
    case LowPassKind::kButterworth2: return "butterworth2";
    case LowPassKind::kFirstOrderBilinear: return "first_order_bilinear";
    case LowPassKind::kButterworth2ImpulseInvariant: return "butterworth2_impulse";
    case LowPassKind::kMovingAverage: return "moving_average";
    case LowPassKind::kCic2: return "cic2";
  }
  return "none";
}

bool IsFirLowPass(LowPassKind kind) {
  return kind == LowPassKind::kMovingAverage || kind == LowPassKind::kCic2;
}

std::vector<double> BoxLengths(LowPassKind kind, double cutoff_hz, double internal_rate_hz) {
  static const double kBox = BoxHalfPowerProduct(1), kCic2 = BoxHalfPowerProduct(2);
  if (kind == LowPassKind::kMovingAverage) return {kBox * internal_rate_hz / cutoff_hz};
  if (kind == LowPassKind::kCic2) {
    const double w = kCic2 * internal_rate_hz / cutoff_hz;
    return {w, w};
  }
  return {};
}

std::vector<double> BoxTaps(double w) {
  const auto whole = static_cast<std::size_t>(std::floor(w));
  std::vector<double> taps(whole, 1.0 / w);
  const double frac = w - static_cast<double>(whole);
  if (frac > 0.0) taps.push_back(frac / w);
  return taps;
}

BoxFilter::BoxFilter(double w)
    : whole_(static_cast<std::size_t>(std::floor(w))), frac_(w - std::floor(w)), inv_w_(1.0 / w) {
  ring_.assign(whole_ + 1, 0.0);
}

double BoxFilter::Step(double x) {
  // ring_ holds x_{n-1} .. x_{n-whole-1}; the slot after pos_ is x_{n-whole}, which leaves the
  // whole taps now and takes the fractional one.
  const std::size_t next = pos_ + 1 == ring_.size() ? 0 : pos_ + 1;
  const double leaving = ring_[next];
  ring_[pos_] = x;
  pos_ = next;
  sum_ += x;
  sum_ -= leaving;
  return static_cast<double>((sum_ + frac_ * static_cast<long double>(leaving)) * inv_w_);
}

void BoxFilter::FilterInPlace(std::span<double> x) {
  double* ring = ring_.data();
  const std::size_t size = ring_.size();
  std::size_t pos = pos_;
  long double sum = sum_;
  const double frac = frac_, inv_w = inv_w_;
  for (double& v : x) {
    const std::size_t next = pos + 1 == size ? 0 : pos + 1;
    const double leaving = ring[next];
    const double in = v;
    ring[pos] = in;
    pos = next;
    sum += in;
    sum -= leaving;
    v = static_cast<double>((sum + frac * static_cast<long double>(leaving)) * inv_w);
  }
  pos_ = pos;
  sum_ = sum;
}

bool BandLimit::IsValid(double output_rate_hz, std::string* why) const {
  auto fail = [&](const std::string& msg) {
    if (why) *why = msg;
    return false;
  };
  if (!enabled()) return true;
  if (!std::isfinite(cutoff_hz) || cutoff_hz <= 0.0) {
    return fail("band-limit cutoff fc must be a finite number > 0 Hz");
  }
  if (oversampling < 1 || oversampling > 256) {
    return fail("band-limit oversampling must be an integer in [1, 256], got " +
                std::to_string(oversampling));
  }
  const double internal_nyquist = 0.5 * oversampling * output_rate_hz;
  if (IsFirLowPass(kind)) {
    for (double w : BoxLengths(kind, cutoff_hz, oversampling * output_rate_hz)) {
      if (!(w >= 1.0)) {
        std::ostringstream os;
        os << "band-limit cutoff fc = " << cutoff_hz << " Hz makes the " << LowPassKindName(kind)
           << " filter shorter than one internal sample (" << oversampling << " x " << output_rate_hz
           << " Hz)";
        return fail(os.str());
      }
    }
    return true;
  }
  if (cutoff_hz >= internal_nyquist) {
    std::ostringstream os;
    os << "band-limit cutoff fc = " << cutoff_hz << " Hz is not below the Nyquist frequency "
       << internal_nyquist << " Hz of the internal rate (" << oversampling << " x " << output_rate_hz
       << " Hz)";
    return fail(os.str());
  }
  return true;
}

Biquad DesignLowPass(LowPassKind kind, double cutoff_hz, double internal_rate_hz) {
  Biquad f;
  if (kind == LowPassKind::kFirstOrder) {
    const double a = std::exp(-2.0 * std::numbers::pi * cutoff_hz / internal_rate_hz);
    f.b0 = 1.0 - a;
    f.a1 = -a;
  } else if (kind == LowPassKind::kButterworth2) {
    const double k = std::tan(std::numbers::pi * cutoff_hz / internal_rate_hz);
    const double norm = 1.0 / (1.0 + std::numbers::sqrt2 * k + k * k);
    f.b0 = k * k * norm;
    f.b1 = 2.0 * f.b0;
    f.b2 = f.b0;
    f.a1 = 2.0 * (k * k - 1.0) * norm;
    f.a2 = (1.0 - std::numbers::sqrt2 * k + k * k) * norm;
  } else if (kind == LowPassKind::kFirstOrderBilinear) {
    const double k = std::tan(std::numbers::pi * cutoff_hz / internal_rate_hz);
    f.b0 = k / (1.0 + k);
    f.b1 = f.b0;
    f.a1 = (k - 1.0) / (1.0 + k);
  } else if (kind == LowPassKind::kButterworth2ImpulseInvariant) {
    // h(t) = sqrt(2) wc e^{-a t} sin(a t), a = wc / sqrt(2), sampled: poles e^{(-a +- i a) T}, the
    // response starting one sample late (h(0) = 0); the numerator is rescaled to unit DC gain.
    const double a = 2.0 * std::numbers::pi * cutoff_hz / std::numbers::sqrt2 / internal_rate_hz;
    f.b0 = 0.0;
    f.a1 = -2.0 * std::exp(-a) * std::cos(a);
    f.a2 = std::exp(-2.0 * a);
    f.b1 = 1.0 + f.a1 + f.a2;
  }
  return f;
}

BandLimitChain::BandLimitChain(const BandLimit& limit, double output_rate_hz) : limit_(limit) {
  const int l = limit_.oversampling;
  internal_clock_ = SampleClock::FromRateHz(output_rate_hz * l);
  const double internal_rate_hz = internal_clock_.rate_hz();
  design_ = DesignLowPass(limit_.kind, limit_.cutoff_hz, internal_rate_hz);

  box_lengths_ = BoxLengths(limit_.kind, limit_.cutoff_hz, internal_rate_hz);
  std::vector<double> g;
  if (!box_lengths_.empty()) {
    // The boxes' taps convolved: finite, exact.
    g = {1.0};
    for (double w : box_lengths_) {
      const std::vector<double> box = BoxTaps(w);
      std::vector<double> next(g.size() + box.size() - 1, 0.0);
      for (std::size_t i = 0; i < g.size(); ++i) {
        for (std::size_t j = 0; j < box.size(); ++j) next[i + j] += g[i] * box[j];
      }
      g = std::move(next);
    }
  } else {
    // Impulse response of the filter until it has decayed to 1e-18 of its peak for a full
    // output period (the poles are inside the unit circle, so the envelope decays).
    Biquad f = design_;
    double peak = 0.0;
    int quiet = 0;
    for (std::int64_t n = 0; n < (std::int64_t{1} << 26); ++n) {
      const double v = f.Step(n == 0 ? 1.0 : 0.0);
      g.push_back(v);
      peak = std::max(peak, std::abs(v));
      quiet = peak > 0.0 && std::abs(v) < 1e-18 * peak ? quiet + 1 : 0;
      if (quiet > 2 * l + 4) break;
    }
  }
  if (limit_.sampling == OutputSampling::kAverage) {
    std::vector<double> avg(g.size() + l - 1, 0.0);
    for (std::size_t n = 0; n < g.size(); ++n) {
      for (int i = 0; i < l; ++i) avg[n + i] += g[n] / l;
    }
    g = std::move(avg);
  }
  internal_response_ = g;

  const std::size_t taps = (g.size() + l - 1) / l;
  held_response_.assign(taps, 0.0);
  for (std::size_t n = 0; n < g.size(); ++n) held_response_[n / l] += g[n];
  held_autocorrelation_.assign(taps, 0.0);
  for (std::size_t d = 0; d < taps; ++d) {
    for (std::size_t a = 0; a + d < taps; ++a) {
      held_autocorrelation_[d] += held_response_[a] * held_response_[a + d];
    }
  }
  burn_in_samples_ = static_cast<std::int64_t>(taps) + 1;
}

std::complex<double> BandLimitChain::WidebandGain(double f_hz) const {
  const double w = 2.0 * std::numbers::pi * f_hz * internal_clock_.period_s();
  std::complex<double> sum = 0.0;
  for (std::size_t n = 0; n < internal_response_.size(); ++n) {
    sum += internal_response_[n] * std::polar(1.0, -w * static_cast<double>(n));
  }
  return sum;
}

namespace {

using ComplexLd = std::complex<long double>;

// An IIR chain's response ge_n as a sum of geometric terms from `start` on: ge_{start+t} =
// sum_i c_i p_i^t, p_i the section's poles (the numerator of order <= 2 and the averaging box of
// L have acted by start = 3 + L - 1). The c_i are solved from ge_start and ge_{start+1} and
// checked on ge_{start+2}; count 0 where that fails (a box kind, a response too short, repeated
// poles): the caller sums directly.
struct GeometricTail {
  int count = 0;
  std::array<ComplexLd, 2> pole{}, coef{};
  std::size_t start = 0;
};

GeometricTail TailOf(const Biquad& d, const std::vector<double>& g, int l, bool average) {
  GeometricTail tail;
  tail.start = 3 + (average ? static_cast<std::size_t>(l - 1) : 0);
  if (tail.start + 3 > g.size()) return tail;
  const long double g0 = g[tail.start], g1 = g[tail.start + 1], g2 = g[tail.start + 2];
  if (d.a2 == 0.0) {
    tail.count = 1;
    tail.pole[0] = -static_cast<long double>(d.a1);
    tail.coef[0] = g0;
  } else {
    const ComplexLd disc = std::sqrt(ComplexLd(static_cast<long double>(d.a1) * d.a1 - 4.0L * d.a2));
    tail.pole[0] = (-static_cast<long double>(d.a1) + disc) / 2.0L;
    tail.pole[1] = (-static_cast<long double>(d.a1) - disc) / 2.0L;
    if (std::abs(tail.pole[0] - tail.pole[1]) < 1e-9L) return GeometricTail{};
    tail.count = 2;
    tail.coef[0] = (g1 - tail.pole[1] * g0) / (tail.pole[0] - tail.pole[1]);
    tail.coef[1] = g0 - tail.coef[0];
  }
  ComplexLd predicted = 0.0L;
  for (int i = 0; i < tail.count; ++i) predicted += tail.coef[i] * tail.pole[i] * tail.pole[i];
  long double peak = 0.0L;
  for (double v : g) peak = std::max(peak, static_cast<long double>(std::abs(v)));
  if (std::abs(predicted.real() - g2) > 1e-12L * peak) return GeometricTail{};
  return tail;
}

}  // namespace

std::vector<double> BandLimitChain::WhiteOutputAutocovariance(double internal_variance,
                                                              std::int64_t lags) const {
  const auto& g = internal_response_;
  const std::int64_t l = limit_.oversampling;
  std::vector<double> r(static_cast<std::size_t>(lags), 0.0);
  // The lags whose shift j L lies within the (truncated) response; zero beyond, as its sum is.
  const std::int64_t support = std::min(lags, (static_cast<std::int64_t>(g.size()) + l - 1) / l);
  const GeometricTail tail = box_lengths_.empty()
                                 ? TailOf(design_, g, limit_.oversampling,
                                          limit_.sampling == OutputSampling::kAverage)
                                 : GeometricTail{};
  if (tail.count == 0) {
    for (std::int64_t j = 0; j < support; ++j) {
      const auto shift = static_cast<std::size_t>(j * l);
      long double s = 0.0L;
      for (std::size_t n = 0; n + shift < g.size(); ++n) s += g[n] * g[n + shift];
      r[static_cast<std::size_t>(j)] = static_cast<double>(internal_variance * s);
    }
    return r;
  }
  // sum_n ge_n ge_{n+k} in closed form, O(start) per lag instead of O(len(ge)) (a low cutoff's
  // response is long, and the baseline's band-limit search builds a chain per cutoff): the head
  // n < start term by term (ge_{n+k} from the tail once n + k reaches it), and the tail's
  // sum_{t>=0} ge_{start+t} ge_{start+t+k} = sum_{i,j} c_i c_j p_j^k / (1 - p_i p_j). The tail runs
  // on past the truncation (by less than 1e-18 of the peak).
  const std::size_t start = tail.start;
  std::array<ComplexLd, 2> step{}, power{};  // p_i^L and p_i^k, k = j L
  for (int i = 0; i < tail.count; ++i) {
    step[i] = std::pow(tail.pole[i], static_cast<int>(l));
    power[i] = 1.0L;
  }
  auto tail_at = [&](std::size_t m) {  // ge_m for m >= start
    ComplexLd v = 0.0L;
    for (int i = 0; i < tail.count; ++i) v += tail.coef[i] * std::pow(tail.pole[i], static_cast<int>(m - start));
    return v.real();
  };
  for (std::int64_t j = 0; j < support; ++j) {
    const auto k = static_cast<std::size_t>(j * l);
    long double s = 0.0L;
    for (std::size_t n = 0; n < start; ++n) {
      s += static_cast<long double>(g[n]) * (n + k < start ? static_cast<long double>(g[n + k]) : tail_at(n + k));
    }
    ComplexLd t = 0.0L;
    for (int a = 0; a < tail.count; ++a) {
      for (int b = 0; b < tail.count; ++b) {
        t += tail.coef[a] * tail.coef[b] * power[b] / (1.0L - tail.pole[a] * tail.pole[b]);
      }
    }
    s += t.real();
    r[static_cast<std::size_t>(j)] = static_cast<double>(internal_variance * s);
    for (int i = 0; i < tail.count; ++i) power[i] *= step[i];
  }
  return r;
}

std::vector<double> BandLimitChain::HeldOutputAutocovariance(const std::vector<double>& r_in,
                                                             std::int64_t lags) const {
  // Double sums, j in the inner loop so that it vectorises: called once per model with a
  // record's worth of lags, the scalar long-double loop was 13 % of diagnose's CPU on the
  // ADIS16405 Z record. Each lag's sum runs in one order, rq[0] x_j first, then d = 1, 2, ...;
  // it rounds once per tap (tests/sim/held_output_autocovariance_test.cc holds it to that).
  const auto& rq = held_autocorrelation_;
  const std::int64_t taps = static_cast<std::int64_t>(rq.size());
  const double* x = r_in.data();
  std::vector<double> r(static_cast<std::size_t>(lags));
  // Lags below taps reach negative j - d: the generalised autocovariance is even.
  const std::int64_t edge = std::min(lags, taps);
  for (std::int64_t j = 0; j < edge; ++j) {
    double s = rq[0] * x[j];
    for (std::int64_t d = 1; d < taps; ++d) s += rq[d] * (x[j + d] + x[j - d < 0 ? d - j : j - d]);
    r[static_cast<std::size_t>(j)] = s;
  }
  constexpr std::int64_t kBlock = 2048;  // a block of r and its taps' inputs stay in L1/L2
  for (std::int64_t begin = edge; begin < lags; begin += kBlock) {
    const std::int64_t end = std::min(lags, begin + kBlock);
    double* out = r.data();
    for (std::int64_t j = begin; j < end; ++j) out[j] = rq[0] * x[j];
    for (std::int64_t d = 1; d < taps; ++d) {
      const double w = rq[d];
      for (std::int64_t j = begin; j < end; ++j) out[j] += w * (x[j + d] + x[j - d]);
    }
  }
  return r;
}

const std::vector<BandLimitFamily>& BandLimitFamilies() {
  using K = LowPassKind;
  using S = OutputSampling;
  static const std::vector<BandLimitFamily> families = {
      {"analog1_point", K::kFirstOrder, 8, S::kPoint, 1},
      {"analog1_average", K::kFirstOrder, 8, S::kAverage, 1},
      {"analog2_point", K::kButterworth2, 8, S::kPoint, 2},
      {"analog2_average", K::kButterworth2, 8, S::kAverage, 2},
      {"digital1_impulse", K::kFirstOrder, 1, S::kPoint, 1},
      {"digital1_bilinear", K::kFirstOrderBilinear, 1, S::kPoint, 1},
      {"digital2_impulse", K::kButterworth2ImpulseInvariant, 1, S::kPoint, 2},
      {"digital2_bilinear", K::kButterworth2, 1, S::kPoint, 2},
      {"moving_average", K::kMovingAverage, 8, S::kPoint, 1},
      {"cic2", K::kCic2, 8, S::kPoint, 2},
  };
  return families;
}

const BandLimitFamily* FamilyOf(const BandLimit& limit) {
  for (const BandLimitFamily& f : BandLimitFamilies()) {
    if (f.kind == limit.kind && f.oversampling == limit.oversampling &&
        (f.sampling == limit.sampling || f.oversampling == 1)) {
      return &f;
    }
  }
  return nullptr;
}

std::shared_ptr<const BandLimitChain> SharedBandLimitChain(const BandLimit& limit, double output_rate_hz) {
  struct Entry {
    BandLimit limit;
    double rate_hz;
    std::shared_ptr<const BandLimitChain> chain;
  };
  constexpr std::size_t kEntries = 8;  // a fit's central differences visit a handful of cutoffs
  thread_local std::vector<Entry> cache;
  for (const Entry& e : cache) {
    if (e.limit.kind == limit.kind && e.limit.cutoff_hz == limit.cutoff_hz &&
        e.limit.oversampling == limit.oversampling && e.limit.sampling == limit.sampling &&
        e.rate_hz == output_rate_hz) {
      return e.chain;
    }
  }
  auto chain = std::make_shared<const BandLimitChain>(limit, output_rate_hz);
  if (cache.size() >= kEntries) cache.erase(cache.begin());
  cache.push_back({limit, output_rate_hz, chain});
  return chain;
}

}  // namespace allanlab::sim
