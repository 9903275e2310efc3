#pragma once
// The closed set of noise terms a sensor model sums. Adding a term means adding its type here.
#include <string_view>
#include <type_traits>
#include <variant>

#include "sim/bias_step.h"
#include "sim/exponential_drift.h"
#include "sim/flicker_gauss_markov_sum.h"
#include "sim/flicker_noise.h"
#include "sim/gauss_markov.h"
#include "sim/harmonic.h"
#include "sim/outliers.h"
#include "sim/quantization_noise.h"
#include "sim/random_telegraph.h"
#include "sim/random_walk_rate.h"
#include "sim/rate_ramp.h"
#include "sim/white_rate_noise.h"

namespace allanlab::sim {

using NoiseTerm =
    std::variant<QuantizationNoise, WhiteRateNoise, FlickerNoise, FlickerGaussMarkovSum,
                 RandomWalkRate, RateRamp, Harmonic, GaussMarkov, RandomTelegraph,
                 ExponentialDrift, BiasStep, Outliers>;

inline std::string_view TermId(const NoiseTerm& term) {
  return std::visit([](const auto& t) { return std::remove_cvref_t<decltype(t)>::kId; }, term);
}

}  // namespace allanlab::sim
