#include "sim/flicker_gauss_markov_sum.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "sim/gauss_markov.h"

namespace allanlab::sim {

bool FlickerGaussMarkovSum::IsValid(std::string* why) const {
  if (!CheckNonNegative(bias_instability_rad_per_s, "bias instability B", why) ||
      !CheckPositive(min_correlation_time_s, "gm-sum min correlation time", why) ||
      !CheckPositive(max_correlation_time_s, "gm-sum max correlation time", why) ||
      !CheckPositive(processes_per_decade, "gm-sum processes per decade", why)) {
    return false;
  }
  if (max_correlation_time_s <= min_correlation_time_s) {
    if (why) *why = "gm-sum max correlation time must exceed the min correlation time";
    return false;
  }
  if (CorrelationTimes().size() > 200) {
    if (why) *why = "gm-sum bank would have more than 200 processes";
    return false;
  }
  return true;
}

std::vector<double> FlickerGaussMarkovSum::CorrelationTimes() const {
  const double decades = std::log10(max_correlation_time_s / min_correlation_time_s);
  const auto count = static_cast<int>(std::lround(decades * processes_per_decade)) + 1;
  std::vector<double> tc;
  for (int i = 0; i < count; ++i) {
    tc.push_back(min_correlation_time_s * std::pow(10.0, i / processes_per_decade));
  }
  return tc;
}

double FlickerGaussMarkovSum::ProcessVariance() const {
  const double ln_ratio = std::log(10.0) / processes_per_decade;
  return bias_instability_rad_per_s * bias_instability_rad_per_s * ln_ratio / std::numbers::pi;
}

void FlickerGaussMarkovSum::AddTo(Engine& engine, double tau0_s, std::span<double> rate) const {
  const double std_dev = std::sqrt(ProcessVariance());
  for (double tc : CorrelationTimes()) AddAr1(engine, std::exp(-tau0_s / tc), std_dev, rate);
}

void FlickerGaussMarkovSum::FillAutocovariance(double tau0_s, std::span<double> r, std::int64_t first_lag) const {
  std::fill(r.begin(), r.end(), 0.0);
  std::vector<double> one(r.size());
  for (double tc : CorrelationTimes()) {
    FillAr1Autocovariance(std::exp(-tau0_s / tc), ProcessVariance(), one, first_lag);
    for (std::size_t j = 0; j < r.size(); ++j) r[j] += one[j];
  }
}

double FlickerGaussMarkovSum::ExpectedAvar(std::int64_t m, double tau0_s,
                                           const RecordShape&) const {
  double sum = 0.0;
  for (double tc : CorrelationTimes()) sum += Ar1Avar(m, std::exp(-tau0_s / tc), ProcessVariance());
  return sum;
}

double FlickerGaussMarkovSum::AsymptoticAvar(double tau_s) const {
  double sum = 0.0;
  const double sigma = std::sqrt(ProcessVariance());
  for (double tc : CorrelationTimes()) sum += GaussMarkov{sigma, tc}.AsymptoticAvar(tau_s);
  return sum;
}

std::pair<double, double> FlickerGaussMarkovSum::AvarRipple(double tau_lo_s, double tau_hi_s) const {
  const double floor = 2.0 * std::numbers::ln2 / std::numbers::pi * bias_instability_rad_per_s *
                       bias_instability_rad_per_s;
  double lo = 1e300, hi = -1e300;
  constexpr int kPoints = 400;
  for (int i = 0; i <= kPoints; ++i) {
    const double tau = tau_lo_s * std::pow(tau_hi_s / tau_lo_s, static_cast<double>(i) / kPoints);
    const double ratio = AsymptoticAvar(tau) / floor;
    lo = std::min(lo, ratio);
    hi = std::max(hi, ratio);
  }
  return {lo, hi};
}

}  // namespace allanlab::sim
