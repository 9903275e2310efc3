#pragma once
// Band-limiting of the sensor (about 100 Hz for the MEMS gyros of the seed paper), modelled the way
// a real sensor does it: the analog chain runs at an internal rate L times the output rate, a
// low-pass filter acts there, and the output is either point-sampled from it or the mean of the
// L internal samples of each output period (docs/theory.md §2.9).
#include <complex>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace allanlab::sim {

enum class LowPassKind {
  kNone,
  kFirstOrder,    // RC low-pass, time constant 1/(2 pi fc), impulse-invariant at the internal rate
  kButterworth2,  // 2nd-order Butterworth, bilinear transform with pre-warping at fc
};
enum class OutputSampling { kPoint, kAverage };

struct BandLimit {
  LowPassKind kind = LowPassKind::kNone;
  double cutoff_hz = 100.0;  // fc (-3 dB), must be below the internal Nyquist frequency
  int oversampling = 8;      // L: internal rate / output rate
  OutputSampling sampling = OutputSampling::kPoint;

  bool enabled() const { return kind != LowPassKind::kNone; }
  // fc > 0, L in [1, 256], fc < L * fs / 2.
  bool IsValid(double output_rate_hz, std::string* why) const;
};

// y[i] = b0 x[i] + b1 x[i-1] + b2 x[i-2] - a1 y[i-1] - a2 y[i-2] (transposed direct form II).
struct Biquad {
  double b0 = 1.0, b1 = 0.0, b2 = 0.0, a1 = 0.0, a2 = 0.0;
  double z1 = 0.0, z2 = 0.0;
  double Step(double x) {
    const double y = b0 * x + z1;
    z1 = b1 * x - a1 * y + z2;
    z2 = b2 * x - a2 * y;
    return y;
  }
};

// The band-limit at a given output rate, with everything the generator and the exact theory need.
class BandLimitChain {
 public:
  // Precondition: limit.IsValid(output_rate_hz).
  BandLimitChain(const BandLimit& limit, double output_rate_hz);

  const BandLimit& limit() const { return limit_; }
  int oversampling() const { return limit_.oversampling; }
  double internal_period_s() const { return internal_period_s_; }
  Biquad MakeFilter() const { return design_; }

  // ge_n: response of the output (at internal index kL + L - 1) to a unit impulse at internal
  // index kL + L - 1 - n: the filter's impulse response, averaged over a box of L when the output
  // is the mean. Truncated where |ge_n| falls below 1e-18 of its peak.
  const std::vector<double>& internal_response() const { return internal_response_; }
  // q_j = sum_{n=jL}^{jL+L-1} ge_n: the output-rate filter seen by a term held over each output
  // period. Sums to 1 (unit DC gain).
  const std::vector<double>& held_response() const { return held_response_; }
  // Output samples the generator discards first so that every output is in steady state.
  std::int64_t burn_in_samples() const { return burn_in_samples_; }
  // Complex gain sum_n ge_n e^{-i 2 pi f n tau_i} of the chain for a wideband sinusoid at f_hz.
  std::complex<double> WidebandGain(double f_hz) const;
  // Autocovariance at output lags 0..lags-1 of white internal-rate noise of variance
  // `internal_variance` passed through the chain: R(j) = var * sum_n ge_n ge_{n+jL}.
  std::vector<double> WhiteOutputAutocovariance(double internal_variance, std::int64_t lags) const;
  // Generalised autocovariance at output lags 0..lags-1 of a held term with generalised
  // autocovariance `r_in` (lags 0..lags+len(q)-1): R_y(j) = sum_d rq(d) R_x(j + d).
  std::vector<double> HeldOutputAutocovariance(const std::vector<double>& r_in,
                                               std::int64_t lags) const;
  // rq(d) = sum_a q_a q_{a+d}, d = 0..len(q)-1: the autocorrelation of held_response() (even in
  // d, two-sided sum 1).
  const std::vector<double>& held_autocorrelation() const { return held_autocorrelation_; }

 private:
  BandLimit limit_;
  double internal_period_s_ = 0.0;
  Biquad design_;
  std::vector<double> internal_response_;
  std::vector<double> held_response_;
  std::vector<double> held_autocorrelation_;  // rq(d), d = 0..len(q)-1
  std::int64_t burn_in_samples_ = 0;
};

// Low-pass design at the internal rate (unit DC gain).
Biquad DesignLowPass(LowPassKind kind, double cutoff_hz, double internal_rate_hz);

// BandLimitChain(limit, output_rate_hz) memoised per thread (the last few distinct arguments):
// building one is O(len(q)^2) (its held autocorrelation), and fits, theory and every simulated
// record of an envelope ask for the same chain again and again. Same object, so the same bits.
std::shared_ptr<const BandLimitChain> SharedBandLimitChain(const BandLimit& limit, double output_rate_hz);

}  // namespace allanlab::sim
