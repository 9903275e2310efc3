#include "sim/band_limited_avar.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <functional>
#include <memory>
#include <type_traits>

#include <boost/math/special_functions/digamma.hpp>

namespace allanlab::sim {
namespace {

// phi(x), x = 0..len(rq)-1 (header): how far rq smooths the kink of |x|. With rq even,
// |x + d| + |x - d| is 2x for d <= x and 2d beyond, so phi(x) = x (rq_0 + 2 sum_{1<=d<=x} rq_d)
// + 2 sum_{d>x} d rq_d - x: O(len(rq)) from running sums (the direct double sum was O(len(rq)^2),
// redone at every cutoff a band-limit fit visits).
std::vector<double> KinkKernel(const std::vector<double>& rq) {
  const auto taps = static_cast<std::int64_t>(rq.size());
  std::vector<long double> beyond(rq.size(), 0.0L);  // sum_{d>x} d rq_d
  for (std::int64_t d = taps - 1; d >= 1; --d) {
    beyond[static_cast<std::size_t>(d - 1)] = beyond[static_cast<std::size_t>(d)] + static_cast<long double>(d) * rq[d];
  }
  std::vector<double> phi(rq.size(), 0.0);
  long double within = rq[0];  // rq_0 + 2 sum_{1<=d<=x} rq_d
  for (std::int64_t x = 0; x < taps; ++x) {
    if (x > 0) within += 2.0L * rq[x];
    const long double xl = static_cast<long double>(x);
    const long double s = xl * within + 2.0L * beyond[static_cast<std::size_t>(x)];
    phi[static_cast<std::size_t>(x)] = static_cast<double>(s - xl);
  }
  return phi;
}

// KinkKernel of the chain's held autocorrelation, memoised per thread for the last few chains
// (a fit evaluates every term at the same cutoff several times).
std::shared_ptr<const std::vector<double>> SharedKinkKernel(const BandLimitChain& chain) {
  struct Entry {
    BandLimit limit;
    double internal_period_s;
    std::shared_ptr<const std::vector<double>> phi;
  };
  constexpr std::size_t kEntries = 8;
  thread_local std::vector<Entry> cache;
  const BandLimit& limit = chain.limit();
  for (const Entry& e : cache) {
    if (e.limit.kind == limit.kind && e.limit.cutoff_hz == limit.cutoff_hz &&
        e.limit.oversampling == limit.oversampling && e.limit.sampling == limit.sampling &&
        e.internal_period_s == chain.internal_period_s()) {
      return e.phi;
    }
  }
  auto phi = std::make_shared<const std::vector<double>>(KinkKernel(chain.held_autocorrelation()));
  if (cache.size() >= kEntries) cache.erase(cache.begin());
  cache.push_back({limit, chain.internal_period_s(), phi});
  return phi;
}

// sum_{i=1..k} 1/(2i - 1) in long double, summed in order, k = 0..kDirectOddHarmonics - 1: the
// running sums the flicker window below starts from (the same bits as summing to k at each call,
// which was a chain of up to 4096 divisions per tau at every band-limited fit evaluation).
constexpr std::int64_t kDirectOddHarmonics = 4096;
const std::vector<long double>& OddHarmonicPrefix() {
  static const std::vector<long double> prefix = [] {
    std::vector<long double> h(static_cast<std::size_t>(kDirectOddHarmonics), 0.0L);
    long double running = 0.0L;
    for (std::int64_t i = 1; i < kDirectOddHarmonics; ++i) {
      running += 1.0L / (2.0L * i - 1.0L);
      h[static_cast<std::size_t>(i)] = running;
    }
    return h;
  }();
  return prefix;
}

// R_x at lags lo..lo+n-1 of a held term. Random walk and Kasdin flicker in closed form (their
// windows sit at lags up to 2m + len(q), which filling from lag 0 would make O(m)); the other
// terms through their FillAutocovariance.
template <typename T>
std::vector<long double> LagWindow(const T& t, double tau0_s, std::int64_t lo, std::int64_t n) {
  std::vector<long double> r(static_cast<std::size_t>(n));
  if constexpr (std::is_same_v<T, RandomWalkRate>) {
    const long double step_var = static_cast<long double>(t.rrw_rad_per_s_per_sqrt_s) *
                                 t.rrw_rad_per_s_per_sqrt_s * tau0_s;
    for (std::int64_t i = 0; i < n; ++i) r[i] = -0.5L * static_cast<long double>(lo + i) * step_var;
  } else if constexpr (std::is_same_v<T, FlickerNoise>) {
    // R(k) = -(2 B^2 / pi) sum_{i=1..k} 1/(2i - 1) (FlickerNoise::FillAutocovariance), the sum
    // being (psi(k + 1/2) - psi(1/2)) / 2; summed directly while that is cheap.
    const long double scale = 2.0L * t.bias_instability_rad_per_s * t.bias_instability_rad_per_s /
                              std::numbers::pi_v<long double>;
    long double h = 0.0L;
    if (lo < kDirectOddHarmonics) {
      h = OddHarmonicPrefix()[static_cast<std::size_t>(lo)];
    } else {
      h = 0.5L * (boost::math::digamma(static_cast<long double>(lo) + 0.5L) -
                  boost::math::digamma(0.5L));
    }
    for (std::int64_t i = 0; i < n; ++i) {
      if (i > 0) h += 1.0L / (2.0L * static_cast<long double>(lo + i) - 1.0L);
      r[i] = -scale * h;
    }
  } else if constexpr (requires(std::span<double> w) { t.FillAutocovariance(tau0_s, w, lo); }) {
    // Only the window: filling from lag 0 made each tau O(m) (Gauss-Markov + band-limit fits of
    // a 1e6 record spent minutes in expm1).
    std::vector<double> window(static_cast<std::size_t>(n));
    t.FillAutocovariance(tau0_s, window, lo);
    for (std::int64_t i = 0; i < n; ++i) r[i] = window[static_cast<std::size_t>(i)];
  } else {
    std::vector<double> full(static_cast<std::size_t>(lo + n));
    t.FillAutocovariance(tau0_s, full);
    for (std::int64_t i = 0; i < n; ++i) r[i] = full[static_cast<std::size_t>(lo + i)];
  }
  return r;
}

template <typename T>
concept HasAutocovariance = requires(const T& t, std::span<double> r) {
  t.FillAutocovariance(1.0, r);
};

// sum_{|x| < len(phi)} phi(|x|) R(|c + x|) for a window centre c >= 0.
template <typename T>
long double KinkSum(const T& t, double tau0_s, const std::vector<double>& phi, std::int64_t c) {
  const auto taps = static_cast<std::int64_t>(phi.size());
  const std::int64_t lo = std::max<std::int64_t>(0, c - (taps - 1));
  const std::int64_t hi = c + taps - 1;
  const std::vector<long double> r = LagWindow(t, tau0_s, lo, hi - lo + 1);
  auto at = [&](std::int64_t lag) { return r[static_cast<std::size_t>(std::abs(lag) - lo)]; };
  long double s = 0.0L;
  for (std::int64_t x = -(taps - 1); x < taps; ++x) s += phi[static_cast<std::size_t>(std::abs(x))] * at(c + x);
  return s;
}

// AR(1) terms (Gauss-Markov, telegraph): R(k) - R(0) = v expm1(k ln phi), so a window wholly at
// positive lags (c >= len(phi) - 1) sums in closed form, KinkSum(c) = v (expm1(c ln phi) P +
// phi^c B) with P = sum phi(|x|), B = sum phi(|x|) expm1(x ln phi) taken once per term: O(1) per
// tau instead of O(len phi) expm1 calls (30 % of a band-limited Gauss-Markov diagnosis' CPU).
// expm1 keeps both parts accurate when phi -> 1.
struct Ar1Kink {
  double variance = 0.0, log_phi = 0.0;
  long double p = 0.0L, b = 0.0L;
  Ar1Kink(double phi_per_sample, double v, const std::vector<double>& phi) : variance(v), log_phi(std::log(phi_per_sample)) {
    const auto taps = static_cast<std::int64_t>(phi.size());
    for (std::int64_t x = -(taps - 1); x < taps; ++x) {
      const long double w = phi[static_cast<std::size_t>(std::abs(x))];
      p += w;
      b += w * std::expm1(static_cast<long double>(x) * log_phi);
    }
  }
  long double At(std::int64_t c) const {
    const long double cl = static_cast<long double>(c) * log_phi;
    return variance * (std::expm1(cl) * p + std::exp(cl) * b);
  }
};

// The resonance (R(k) = Re[w e^{k L}], complex L; resonance.h; its own R, not R - R(0)):
// KinkSum(c) = Re[w e^{c L} S], S = sum phi(|x|) e^{x L} taken once per term: one complex
// exponential per tau instead of 2 len(phi) exp and sincos calls (the fits re-evaluate the
// kink sums at every step: 16 % of a band-limited resonance diagnosis' CPU, the ADIS16405 Z axis).
// No cancellation to guard against as e^L -> 1: S tends to sum phi(|x|) > 0 (phi >= 0, |x| being
// convex and rq a unit-sum average).
struct ComplexPoleKink {
  std::complex<double> weight, log_pole, s;
  ComplexPoleKink(const Resonance::GeometricForm& g, const std::vector<double>& phi)
      : weight(g.weight), log_pole(g.log_pole) {
    const std::complex<double> z = std::exp(log_pole), inverse = 1.0 / z;
    std::complex<double> up = 1.0, down = 1.0;
    s = phi[0];
    for (std::size_t x = 1; x < phi.size(); ++x) {
      up *= z;
      down *= inverse;
      s += phi[x] * (up + down);
    }
  }
  long double At(std::int64_t c) const {
    const double cd = static_cast<double>(c);
    return std::real(weight * std::polar(std::exp(cd * log_pole.real()), cd * log_pole.imag()) * s);
  }
};

bool Ar1Of(const GaussMarkov& t, double tau0_s, double* phi, double* v) {
  *phi = std::exp(-tau0_s / t.correlation_time_s);
  *v = t.sigma_rad_per_s * t.sigma_rad_per_s;
  return true;
}
bool Ar1Of(const RandomTelegraph& t, double tau0_s, double* phi, double* v) {
  *phi = std::exp(-2.0 * tau0_s / t.mean_dwell_s);
  *v = t.amplitude_rad_per_s * t.amplitude_rad_per_s;
  return true;
}

struct Change {
  const BandLimitChain& chain;
  double tau0_s;
  std::span<const std::int64_t> ms;
  std::vector<double>* out;

  bool operator()(const WhiteRateNoise& t) const {
    // Output autocovariance over its whole support (zero beyond: the response is truncated).
    const double internal_var = t.arw_rad_per_sqrt_s * t.arw_rad_per_sqrt_s / chain.internal_period_s();
    const auto support = static_cast<std::int64_t>(chain.internal_response().size()) /
                             chain.oversampling() + 2;
    const std::vector<double> r = chain.WhiteOutputAutocovariance(internal_var, support);
    out->clear();
    for (std::int64_t m : ms) {
      long double sum = static_cast<long double>(2 * m) * r[0];
      for (std::int64_t j = 1; j < std::min(2 * m, support); ++j) {
        sum += 2.0L * AllanLagWeight(m, j) * static_cast<long double>(r[static_cast<std::size_t>(j)]);
      }
      const long double md = static_cast<long double>(m);
      const long double filtered = sum / (2.0L * md * md);
      const long double own = static_cast<long double>(t.arw_rad_per_sqrt_s) * t.arw_rad_per_sqrt_s /
                              (md * tau0_s);
      out->push_back(static_cast<double>(filtered - own));
    }
    return true;
  }
  bool operator()(const Harmonic&) const { return false; }
  template <typename T>
  bool operator()(const T& t) const {
    out->clear();
    if constexpr (T::kPath == SignalPath::kDigital || std::is_same_v<T, RateRamp>) {
      out->assign(ms.size(), 0.0);
      return true;
    } else if constexpr (HasAutocovariance<T>) {
      const std::shared_ptr<const std::vector<double>> kernel = SharedKinkKernel(chain);
      const std::vector<double>& phi = *kernel;
      const long double at_zero = KinkSum(t, tau0_s, phi, 0);
      std::function<long double(std::int64_t)> kink = [&](std::int64_t c) { return KinkSum(t, tau0_s, phi, c); };
      if constexpr (std::is_same_v<T, GaussMarkov> || std::is_same_v<T, RandomTelegraph>) {
        double phi_per_sample = 0.0, variance = 0.0;
        Ar1Of(t, tau0_s, &phi_per_sample, &variance);
        const auto first_closed = static_cast<std::int64_t>(phi.size()) - 1;
        // phi^x at the window's negative offsets must stay finite (a correlation far shorter
        // than a sample: ln phi = -50 over hundreds of taps overflows).
        if (static_cast<double>(first_closed) * std::abs(std::log(phi_per_sample)) < 200.0) {
          const auto ar1 = std::make_shared<Ar1Kink>(phi_per_sample, variance, phi);
          kink = [&, ar1, first_closed](std::int64_t c) {
            return c >= first_closed ? ar1->At(c) : KinkSum(t, tau0_s, phi, c);
          };
        }
      } else if constexpr (std::is_same_v<T, Resonance>) {
        const Resonance::GeometricForm g = t.Geometric(tau0_s);
        const auto first_closed = static_cast<std::int64_t>(phi.size()) - 1;
        if (static_cast<double>(first_closed) * std::abs(g.log_pole.real()) < 200.0) {
          const auto pole = std::make_shared<ComplexPoleKink>(g, phi);
          kink = [&, pole, first_closed](std::int64_t c) {
            return c >= first_closed ? pole->At(c) : KinkSum(t, tau0_s, phi, c);
          };
        }
      }
      for (std::int64_t m : ms) {
        const long double md = static_cast<long double>(m);
        const long double s = -3.0L * at_zero + 4.0L * kink(m) - kink(2 * m);
        out->push_back(static_cast<double>(s / (2.0L * md * md)));
      }
      return true;
    } else {
      (void)t;
      return false;
    }
  }
};

}  // namespace

bool BandLimitAvarChange(const NoiseTerm& term, const BandLimitChain& chain, double tau0_s,
                         std::span<const std::int64_t> ms, std::vector<double>* change) {
  std::vector<double> out;
  out.reserve(ms.size());
  if (!std::visit(Change{chain, tau0_s, ms, &out}, term)) return false;
  *change = std::move(out);
  return true;
}

}  // namespace allanlab::sim
