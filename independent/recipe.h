#pragma once
// What an independent test record is made of: a gyro's noise terms, the sensor's digital chain
// and the effects a real sensor adds, in SI units (rates in rad/s). Written apart from sim/ and
// from the diagnosis candidates so that tests of those codes can use records they did not make:
// other discretizations (continuous-time processes averaged over each sample interval instead of
// point-sampled discrete processes), other parameterizations (flicker by its Allan floor, the
// telegraph by its continuous dwell time), other random numbers (random_stream.h) and noise laws.
//
// Signal chain of Generate (generate.h), in this order:
//   1. wideband white rate noise (ARW) at the internal rate fs * L (L = low_pass.oversampling when
//      a low-pass is set, else 1): the mean rate over each internal step of a Wiener angle, with
//      a Gaussian, Student-t or Laplace law of the same variance N^2 / tau_int;
//   2. the low-pass at the internal rate, then decimation to fs (point-sampled or averaged over
//      the L internal samples; a CIC filter is K cascaded moving sums of length L then point
//      decimation);
//   3. the slow terms and effects at the output rate, each the exact mean over the sample
//      interval of a continuous-time signal (flicker is an exact discrete spectrum instead):
//      bias, flicker, rate random walk, rate ramp, Gauss-Markov, random telegraph, sinusoid,
//      bias step, warm-up drift, and the resonance (point-sampled: a mechanical mode's state);
//   4. the output quantizers (angle with carry, or rate with optional subtractive dither);
//   5. spikes (data-link glitches: after everything else).
// The low-pass acts on the wideband noise only: the slow terms are far below any cutoff allowed
// here and pass with unit gain; this keeps every expected Allan variance in closed form.
#include <cstdint>
#include <optional>
#include <string>

namespace allanlab::independent {

enum class WhiteLaw { kGaussian, kStudentT, kLaplace };

struct Noise {
  double arw_rad_per_sqrt_s = 0.0;  // N: white rate PSD N^2 (two-sided, per Hz): AVAR N^2 / tau
  WhiteLaw white_law = WhiteLaw::kGaussian;
  double student_t_dof = 5.0;  // > 4 (finite kurtosis); the draws are scaled to unit variance
  // Bias instability given as the flicker's Allan deviation floor (rad/s): the flat ADEV level of
  // the flicker part, 0.6643 B with IEEE 952's B (IEEE's S = B^2 / (2 pi f) enters its AVAR
  // integral with a factor 4, i.e. the one-sided PSD is B^2 / (pi f)).
  double flicker_floor_rad_per_s = 0.0;
  double rrw_rad_per_s_per_sqrt_s = 0.0;  // K: AVAR K^2 tau / 3
  double ramp_rad_per_s2 = 0.0;           // R: AVAR R^2 tau^2 / 2
  double bias_rad_per_s = 0.0;            // constant offset (no Allan variance)
};

enum class LowPassDesign {
  kNone,
  kFirstOrderImpulseInvariant,   // y = a y[-1] + (1 - a) x, a = exp(-2 pi fc / fs_int)
  kFirstOrderBilinear,           // RC low-pass by the bilinear transform, pre-warped at fc
  kSecondOrderImpulseInvariant,  // Butterworth poles mapped by exp(s T), DC gain 1
  kSecondOrderBilinear,          // Butterworth by the bilinear transform, pre-warped at fc
  kCic,                          // `cic_stages` cascaded moving averages of length L
};
enum class Decimation { kPoint, kAverage };

struct LowPass {
  LowPassDesign design = LowPassDesign::kNone;
  double cutoff_hz = 0.0;  // -3 dB of the analog prototype (unused by kCic)
  int oversampling = 8;    // L = internal rate / output rate
  Decimation decimation = Decimation::kAverage;  // unused by kCic (always point)
  int cic_stages = 3;
};

struct GaussMarkov {
  double sigma_rad_per_s = 0.0;     // stationary std of the continuous process
  double correlation_time_s = 0.0;  // autocovariance sigma^2 exp(-|t| / Tc)
};
struct Telegraph {
  double amplitude_rad_per_s = 0.0;  // the rate is +a or -a
  double mean_dwell_s = 0.0;         // flips are a Poisson process of rate 1 / mean_dwell
};
struct Sinusoid {
  double amplitude_rad_per_s = 0.0;
  double frequency_hz = 0.0;
  std::optional<double> phase_rad;  // nullopt: uniform random
};
struct Resonance {  // x'' + 2 zeta w0 x' + w0^2 x = white, x the rate; point-sampled
  double sigma_rad_per_s = 0.0;  // stationary std of x
  double frequency_hz = 0.0;     // f0 = w0 / (2 pi), below fs / 2
  double damping_ratio = 0.05;   // zeta in (0, 1)
};
struct BiasStep {
  double size_rad_per_s = 0.0;  // signed
  double time_s = 0.0;          // rounded to the nearest sample boundary
};
struct WarmupDrift {  // A exp(-t / tau): the bias settling after switch-on
  double amplitude_rad_per_s = 0.0;  // signed
  double time_constant_s = 0.0;
};
struct Spikes {
  double rate_hz = 0.0;          // mean spikes per second (each sample with probability rate / fs)
  double scale_rad_per_s = 0.0;  // smallest magnitude; magnitudes Pareto with `tail_index`
  double tail_index = 3.0;       // > 2 (finite variance); large: nearly fixed size
  bool one_sided = false;        // all positive (else random sign)
};
struct AngleQuantizer {
  double lsb_rad = 0.0;  // the angle is quantized with carry, from a uniform random residual
};
struct RateQuantizer {
  double lsb_rad_per_s = 0.0;
  bool subtractive_dither = false;  // add U(-q/2, q/2) before rounding, subtract after
};

struct Recipe {
  double rate_hz = 100.0;
  Noise noise;
  LowPass low_pass;
  std::optional<GaussMarkov> gauss_markov;
  std::optional<Telegraph> telegraph;
  std::optional<Sinusoid> sinusoid;
  std::optional<Resonance> resonance;
  std::optional<BiasStep> bias_step;
  std::optional<WarmupDrift> warmup_drift;
  std::optional<Spikes> spikes;
  std::optional<AngleQuantizer> angle_quantizer;
  std::optional<RateQuantizer> rate_quantizer;

  double sample_period_s() const { return 1.0 / rate_hz; }
  int internal_oversampling() const { return low_pass.design == LowPassDesign::kNone ? 1 : low_pass.oversampling; }
  // Every value finite and in its domain for records of `num_samples` samples; else false with
  // one line in *why naming the parameter.
  bool IsValid(std::int64_t num_samples, std::string* why) const;
};

// The flicker floor (ADEV) of IEEE 952's bias instability B: sqrt(2 ln 2 / pi) B.
double FlickerFloorFromB(double b_rad_per_s);

}  // namespace allanlab::independent
