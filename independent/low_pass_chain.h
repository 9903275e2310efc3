#pragma once
// The sensor's digital low-pass and decimation (recipe.h LowPass): textbook designs, not sim/'s
// band-limit code. Each filter is one biquad (b0 + b1 z^-1 + b2 z^-2) / (1 + a1 z^-1 + a2 z^-2)
// with DC gain 1, or a CIC: K cascaded moving averages of length L.
#include <span>
#include <vector>

#include "independent/recipe.h"

namespace allanlab::independent {

struct Biquad {
  double b0 = 1.0, b1 = 0.0, b2 = 0.0, a1 = 0.0, a2 = 0.0;
};

// The biquad of `lp` (not kNone, not kCic) at the internal rate internal_rate_hz.
Biquad DesignBiquad(const LowPass& lp, double internal_rate_hz);

// The impulse response of the whole chain from one internal input sample to the internal
// sequence that decimation reads (filter, then the L-sample mean for kAverage), truncated where
// it has fallen below 1e-13 of its peak for good.
std::vector<double> ChainImpulseResponse(const LowPass& lp, double internal_rate_hz);

// Filters `internal` (L * n_out + warm-up samples, the warm-up first) and writes the n_out
// decimated outputs. The warm-up (WarmupSamples) lets the filter reach its stationary state.
void FilterAndDecimate(const LowPass& lp, double internal_rate_hz, std::span<const double> internal,
                       std::span<double> out);
std::int64_t WarmupSamples(const LowPass& lp, double internal_rate_hz);

// Autocovariance at output lags 0..max_lag of the chain's output when its input is white with
// variance `input_variance` per internal sample: R(j) = var sum_i g_i g_{i + j L}.
std::vector<double> OutputAutocovariance(const LowPass& lp, double internal_rate_hz, double input_variance,
                                         std::int64_t max_lag);

}  // namespace allanlab::independent
