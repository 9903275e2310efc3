#pragma once
// Band-limiting of the sensor (about 100 Hz for the MEMS gyros of the seed paper), modelled the way
// a real sensor does it: the analog chain runs at an internal rate L times the output rate, a
// low-pass filter acts there, and the output is either point-sampled from it or the mean of the
// L internal samples of each output period (docs/theory.md §2.9).
#include <complex>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "common/sample_clock.h"

namespace allanlab::sim {

// Every filter has unit DC gain and -3 dB at fc (for the IIR kinds, of the analog prototype).
enum class LowPassKind {
  kNone,
  kFirstOrder,    // RC low-pass, time constant 1/(2 pi fc), impulse-invariant at the internal rate
  kButterworth2,  // 2nd-order Butterworth, bilinear transform with pre-warping at fc
  kFirstOrderBilinear,           // RC low-pass, bilinear transform with pre-warping at fc
  kButterworth2ImpulseInvariant,  // 2nd-order Butterworth, impulse-invariant (DC gain rescaled to 1)
  // Moving average (boxcar) over T = 0.4429 / fc seconds of internal samples (the continuous
  // box's -3 dB point), the last tap weighted by the fractional part of T fs_internal: the
  // averaging or decimation filter of a digital sensor, continuous in fc.
  kMovingAverage,
  // Two such boxes in cascade (2nd-order CIC decimator, triangular response), each 0.3190 / fc
  // long (-3 dB of sinc^2).
  kCic2,
};
std::string_view LowPassKindName(LowPassKind kind);  // YAML name: "first_order", "moving_average", ...
bool IsFirLowPass(LowPassKind kind);                 // the box kinds
enum class OutputSampling { kPoint, kAverage };

struct BandLimit {
  LowPassKind kind = LowPassKind::kNone;
  double cutoff_hz = 100.0;  // fc (-3 dB), must be below the internal Nyquist frequency
  int oversampling = 8;      // L: internal rate / output rate
  OutputSampling sampling = OutputSampling::kPoint;

  bool enabled() const { return kind != LowPassKind::kNone; }
  // fc > 0, L in [1, 256], fc < L * fs / 2; a box at least one internal sample long.
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
  double internal_period_s() const { return internal_clock_.period_s(); }
  Biquad MakeFilter() const { return design_; }
  // The box kinds: lengths of the cascaded boxes in internal samples (real, >= 1); empty for IIR.
  const std::vector<double>& box_lengths() const { return box_lengths_; }

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
  SampleClock internal_clock_;  // oversampling x the output rate
  Biquad design_;
  std::vector<double> box_lengths_;
  std::vector<double> internal_response_;
  std::vector<double> held_response_;
  std::vector<double> held_autocorrelation_;  // rq(d), d = 0..len(q)-1
  std::int64_t burn_in_samples_ = 0;
};

// Low-pass design at the internal rate (unit DC gain); identity for the box kinds.
Biquad DesignLowPass(LowPassKind kind, double cutoff_hz, double internal_rate_hz);
// Length in internal samples of each box of a box kind at this cutoff (empty for IIR kinds).
std::vector<double> BoxLengths(LowPassKind kind, double cutoff_hz, double internal_rate_hz);
// Impulse response of one box of real length w >= 1: floor(w) taps of 1/w, then frac(w)/w.
std::vector<double> BoxTaps(double w);

// A running box filter of real length w (BoxTaps): O(1) per sample whatever its length.
class BoxFilter {
 public:
  explicit BoxFilter(double w);
  double Step(double x);
  // Step over every sample of `x` in order, each output replacing its input: the same arithmetic
  // as Step, with the state held in registers for the whole span (a call per sample kept the
  // long-double sum in memory, and an envelope of an oversampled box band-limit spent a fifth of
  // its time there).
  void FilterInPlace(std::span<double> x);

 private:
  std::vector<double> ring_;  // the last floor(w) + 1 inputs
  std::size_t pos_ = 0;
  std::size_t whole_ = 1;
  double frac_ = 0.0, inv_w_ = 1.0;
  long double sum_ = 0.0L;  // sum of the last `whole_` inputs
};

// A band-limit family the diagnosis fits as one candidate: a filter kind at an oversampling and
// output sampling, named. `analog*` approximate the analog filter by L = 8 internal samples per
// output (point-sampled or averaged over the output period); `digital*` run at the output rate.
struct BandLimitFamily {
  std::string_view name;
  LowPassKind kind;
  int oversampling;
  OutputSampling sampling;
  int order;  // of the filter: 1 or 2 (a box counts as first order, CIC2 as second)
};
const std::vector<BandLimitFamily>& BandLimitFamilies();
// The family of a band-limit, or nullptr if it is none of them.
const BandLimitFamily* FamilyOf(const BandLimit& limit);

// BandLimitChain(limit, output_rate_hz) memoised per thread (the last few distinct arguments):
// building one is O(len(q)^2) (its held autocorrelation), and fits, theory and every simulated
// record of an envelope ask for the same chain again and again. Same object, so the same bits.
std::shared_ptr<const BandLimitChain> SharedBandLimitChain(const BandLimit& limit, double output_rate_hz);

}  // namespace allanlab::sim
