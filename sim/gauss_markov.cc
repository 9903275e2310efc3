#include "sim/gauss_markov.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <unordered_map>
#include <vector>

#include <boost/random/normal_distribution.hpp>

#include "common/thread_memo.h"

namespace allanlab::sim {

namespace {

// P_p(n) = sum_{j=1}^{n} j^p (Faulhaber, Bernoulli B_1 = +1/2), p <= 11.
long double PowerSum(int p, long double n) {
  static constexpr long double kBernoulli[12] = {1.0L, 0.5L, 1.0L / 6, 0.0L, -1.0L / 30, 0.0L,
                                                 1.0L / 42, 0.0L, -1.0L / 30, 0.0L, 5.0L / 66, 0.0L};
  long double sum = 0.0L, binomial = 1.0L;  // C(p + 1, k)
  for (int k = 0; k <= p; ++k) {
    if (kBernoulli[k] != 0.0L) {
      long double power = 1.0L;  // n^(p + 1 - k) by products: powl was a tenth of a band-limit fit
      for (int e = 0; e < p + 1 - k; ++e) power *= n;
      sum += binomial * kBernoulli[k] * power;
    }
    binomial = binomial * static_cast<long double>(p + 1 - k) / static_cast<long double>(k + 1);
  }
  return sum / static_cast<long double>(p + 1);
}

// M_p = sum_j w(j) j^p for p = 1..9 (Ar1Avar's series), which depend on m alone: a fit evaluates
// the series at the same curve's small m for every correlation time it tries, and the power sums
// were most of its cost. Kept per thread (no lock), the same long doubles as computed in place.
const std::array<long double, 9>& SeriesMoments(std::int64_t m) {
  constexpr std::size_t kMaxEntries = 4096;
  thread_local std::unordered_map<std::int64_t, std::array<long double, 9>> kept;
  return ThreadMemo(kept, kMaxEntries, m, [m] {
    const long double ml = static_cast<long double>(m);
    std::array<long double, 9> moments;
    for (int p = 1; p <= 9; ++p) {
      const long double upper_p = PowerSum(p, 2.0L * ml - 1.0L) - PowerSum(p, ml);
      const long double upper_p1 = PowerSum(p + 1, 2.0L * ml - 1.0L) - PowerSum(p + 1, ml);
      moments[static_cast<std::size_t>(p - 1)] =
          2.0L * ml * PowerSum(p, ml) - 3.0L * PowerSum(p + 1, ml) + upper_p1 - 2.0L * ml * upper_p;
    }
    return moments;
  });
}

}  // namespace

double Ar1Avar(std::int64_t m, double phi, double variance) {
  if (variance == 0.0) return 0.0;
  const double log_phi = std::log(phi);
  const double md = static_cast<double>(m);
  const double q = -std::expm1(log_phi);  // 1 - phi
  if (md * q >= 0.01) {
    // Closed form of the lag sum below: m^2 AVAR / variance = m + [2 phi (m q - r) - phi r^2] / q^2
    // with r = 1 - phi^m (Var of a block mean minus the covariance of adjacent ones). O(1) instead
    // of O(m), which the parametric fits evaluate many times. The bracket cancels as m q -> 0
    // (relative error ~ 1e-16 / (m q)^2, below 3e-12 from m q = 0.01), hence the series there.
    const double r = -std::expm1(md * log_phi);
    const double bracket = md + (2.0 * phi * (md * q - r) - phi * r * r) / (q * q);
    return variance * bracket / (md * md);
  }
  // m^2 AVAR / variance = sum_{j=1}^{2m-1} w(j) (phi^j - 1), w the Allan lag weight, expanded in
  // x = -ln(phi): sum_{p>=1} (-x)^p / p! M_p with M_p = sum_j w(j) j^p, polynomials in m (power
  // sums: w is 2m - 3j up to m, j - 2m beyond). Successive terms shrink by ~2 m x / (p + 1) <=
  // 0.02 / (p + 1), so p <= 9 leaves < 1e-20 relative, and no term cancels the first (the lag
  // sum this replaces was O(m) expm1 calls: with Tc >> record, a third of a diagnosis).
  const long double x = -static_cast<long double>(log_phi);
  const long double ml = static_cast<long double>(m);
  const std::array<long double, 9>& moments = SeriesMoments(m);
  long double sum = 0.0L, power = 1.0L;  // power = (-x)^p / p!
  for (int p = 1; p <= 9; ++p) {
    power *= -x / static_cast<long double>(p);
    sum += power * moments[static_cast<std::size_t>(p - 1)];
  }
  return static_cast<double>(variance * sum / (ml * ml));
}

// Below this argument expm1 is -1 exactly: e^x < 2^-54 (x < -37.4) rounds -1 + e^x to -1.
constexpr double kExpm1IsMinusOne = -40.0;

void FillAr1Autocovariance(double phi, double variance, std::span<double> r, std::int64_t first_lag) {
  const double log_phi = std::log(phi);
  for (std::size_t j = 0; j < r.size(); ++j) {
    const double x = static_cast<double>(first_lag + static_cast<std::int64_t>(j)) * log_phi;
    if (x < kExpm1IsMinusOne) {
      // expm1 is -1 exactly from here on (x only falls): the same values without a call per lag.
      std::fill(r.begin() + static_cast<std::ptrdiff_t>(j), r.end(), -variance);
      return;
    }
    r[j] = variance * std::expm1(x);
  }
}

void AddAr1(Engine& engine, double phi, double std_dev, std::span<double> out) {
  if (std_dev == 0.0) return;
  boost::random::normal_distribution<double> normal(0.0, 1.0);
  const double innovation_std = std_dev * std::sqrt(-std::expm1(2.0 * std::log(phi)));
  double state = std_dev * normal(engine);
  for (double& v : out) {
    v += state;
    state = phi * state + innovation_std * normal(engine);
  }
}

bool GaussMarkov::IsValid(std::string* why) const {
  return CheckNonNegative(sigma_rad_per_s, "gauss_markov sigma", why) &&
         CheckPositive(correlation_time_s, "gauss_markov correlation time Tc", why);
}

void GaussMarkov::AddTo(Engine& engine, double tau0_s, std::span<double> rate) const {
  AddAr1(engine, std::exp(-tau0_s / correlation_time_s), sigma_rad_per_s, rate);
}

void GaussMarkov::FillAutocovariance(double tau0_s, std::span<double> r, std::int64_t first_lag) const {
  FillAr1Autocovariance(std::exp(-tau0_s / correlation_time_s), sigma_rad_per_s * sigma_rad_per_s,
                        r, first_lag);
}

double GaussMarkov::ExpectedAvar(std::int64_t m, double tau0_s, const RecordShape&) const {
  return Ar1Avar(m, std::exp(-tau0_s / correlation_time_s), sigma_rad_per_s * sigma_rad_per_s);
}

double GaussMarkov::AsymptoticAvar(double tau_s) const {
  const double tc = correlation_time_s;
  const double x = tau_s / tc;
  // 3 - 4e^{-x} + e^{-2x} = 2x - x^3/3 + ... : use the series where the closed form cancels.
  const double bracket = x < 1e-3 ? 2.0 * x * x * x / 3.0 - x * x * x * x / 2.0
                                  : 2.0 * x - (3.0 - 4.0 * std::exp(-x) + std::exp(-2.0 * x));
  // (2 s^2 Tc / tau)[1 - (1/(2x))(3 - 4e^-x + e^-2x)] = (s^2 / x^2) * bracket
  return sigma_rad_per_s * sigma_rad_per_s * bracket / (x * x);
}

}  // namespace allanlab::sim
