#pragma once
// A gyro sensor model: a plain sum of noise terms, then the band-limit, then the output
// quantizers, sampled at fs. It generates records and knows their exact expected Allan variance.
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "common/sample_clock.h"
#include "sim/avar_theory.h"
#include "sim/band_limit.h"
#include "sim/flicker_stream_cache.h"
#include "sim/noise_term.h"
#include "sim/output_quantizer.h"

namespace allanlab::sim {

// How SensorModel::ExpectedAvar treats Kasdin flicker behind a band-limit (no other term is
// affected, and without a band-limit both are the same).
enum class FlickerBandLimit {
  // The record's exact expectation: the Kasdin filter from its zero state at the first sample,
  // then the chain (O(N len(q)) set-up and O(N) per m). For judging Monte Carlo records.
  kExact,
  // The flicker's own exact AVAR plus the band-limit's change of its stationary-increment form
  // (band_limited_avar.h): O(len(q)) per m at any cutoff, off by a start-up term below
  // 0.5 (tc + 1)/T of the flicker AVAR (docs/theory.md §2.9). For fits that try many cutoffs.
  kStationaryChange,
};

// Choices in how Generate draws a record that change its random stream but not its law.
struct GenerateOptions {
  // White rate noise behind an IIR band-limit (first- or second-order section, not the box kinds)
  // without harmonics: drawn one output period at a time (section_period.h), at most 3 Gaussian
  // draws per output sample instead of the oversampling L. Exact in distribution; for Monte Carlo
  // envelopes, where only the law matters.
  bool white_per_output_period = false;
  // With a cache: the first Kasdin flicker term draws from stream kSharedFlickerStream of
  // (flicker_seed, trial) instead of its own stream of (seed, trial), so the models generated with
  // one flicker_seed share a flicker record per trial (B times the same unit record), which is
  // synthesised once and then taken from the cache (the same bits either way). nullptr: the term's
  // own stream, synthesised every time.
  FlickerStreamCache* flicker_cache = nullptr;
  std::uint64_t flicker_seed = 0;
};

struct SensorModel {
  std::string name;
  std::string description;
  SampleClock sample_clock = SampleClock::FromRateHz(100.0);  // output rate fs and tau0
  double bias_rad_per_s = 0.0;    // constant turn-on bias (no effect on AVAR; matters to quantizers)
  std::vector<NoiseTerm> terms;
  BandLimit band_limit;
  std::optional<AngleQuantizer> angle_quantizer;
  std::optional<RateQuantizer> rate_quantizer;

  // Every term valid, fs > 0, band-limit below the internal Nyquist frequency, outlier
  // probability per sample <= 1.
  bool IsValid(std::string* why) const;

  // A record of n samples for (seed, trial). Term i draws from stream i of (seed, trial); the
  // angle quantizer from stream kQuantizerStream, the rate quantizer's offset (or its dither)
  // from kRateQuantizerStream. Bit-identical for the same arguments whatever
  // the thread. Precondition: IsValid().
  std::vector<double> Generate(std::uint64_t seed, std::uint64_t trial, std::int64_t n) const;
  // The same with `options` (the first white term's stream then feeds the period draws).
  std::vector<double> Generate(std::uint64_t seed, std::uint64_t trial, std::int64_t n,
                               const GenerateOptions& options) const;

  // Exact E[AVAR_hat(m)] of Generate()'s records (rad/s)^2, band-limit and finite record
  // included. The quantizers' shares come from their error autocovariances on the Gaussian
  // part's (output_quantizer.h): the angle quantizer's exact (its initial residual is uniform),
  // the rate quantizer's exact with random_offset or subtractive dither, the busy-noise limit
  // otherwise.
  // ExpectedAvarIsExact() says which.
  double ExpectedAvar(std::int64_t m, const RecordShape& shape) const;
  // The same for a list of averaging factors (shares the per-term set-up work).
  std::vector<double> ExpectedAvar(std::span<const std::int64_t> ms, const RecordShape& shape,
                                   FlickerBandLimit flicker = FlickerBandLimit::kExact) const;
  bool ExpectedAvarIsExact() const {
    return !rate_quantizer || rate_quantizer->random_offset || rate_quantizer->subtractive_dither;
  }

  // Generalised autocovariance of the Gaussian (linear) part of the output at lags 0..lags-1,
  // band-limit included, for exact estimator variances (docs/theory.md §3.1). Flicker enters with its
  // stationary-increment form (no start-up transient); deterministic terms, harmonics and outliers
  // are left out. The quantizers' errors enter with their exact second moments (so estimator
  // variances treat them as Gaussian: an approximation).
  std::vector<double> GaussianAutocovariance(std::int64_t lags) const;

  // Continuous IEEE 952 sum of the terms' asymptotes at tau (no band-limit, no quantizers).
  double AsymptoticAvar(double tau_s) const;

  static constexpr std::uint64_t kQuantizerStream = 1000;
  static constexpr std::uint64_t kRateQuantizerStream = 1001;  // its random offset or dither
  static constexpr std::uint64_t kSharedFlickerStream = 1002;  // GenerateOptions::flicker_cache

 private:
  // GaussianAutocovariance before the rate quantizer.
  std::vector<double> SignalAutocovariance(std::int64_t lags) const;
  // The angle quantizer's error autocovariance R_e(j) (rad^2) for j < min(lags, L), L the first
  // power-of-4 length past which the angle has moved far beyond an LSB (R_e = 0 there): the
  // signal's autocovariance is only computed as far as the error stays correlated.
  std::vector<double> AngleErrorAutocovariance(std::int64_t lags) const;
};

}  // namespace allanlab::sim
