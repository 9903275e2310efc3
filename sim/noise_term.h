#pragma once
// The closed set of noise terms a sensor model sums. Adding a term means adding its type here.
#include <concepts>
#include <span>
#include <string>
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
#include "sim/resonance.h"
#include "sim/rate_ramp.h"
#include "sim/white_rate_noise.h"

namespace allanlab::sim {

// What every term provides (the term headers document each member's units and theory):
//   kId (stable id used in YAML and JSON), kPath (where it enters the sensor chain),
//   IsValid(why), AddTo(engine, tau0, rate) adding its samples, and ExpectedAvar(m, tau0, shape),
//   its exact expected Allan variance for the discrete samples it produces.
template <typename T>
concept NoiseTermType = requires(const T& t, Engine& engine, std::span<double> rate,
                                 std::string* why, const RecordShape& shape) {
  { T::kId } -> std::convertible_to<std::string_view>;
  { T::kPath } -> std::convertible_to<SignalPath>;
  { t.IsValid(why) } -> std::same_as<bool>;
  t.AddTo(engine, 1.0, rate);
  { t.ExpectedAvar(std::int64_t{1}, 1.0, shape) } -> std::same_as<double>;
};

using NoiseTerm =
    std::variant<QuantizationNoise, WhiteRateNoise, FlickerNoise, FlickerGaussMarkovSum,
                 RandomWalkRate, RateRamp, Harmonic, GaussMarkov, RandomTelegraph,
                 ExponentialDrift, BiasStep, Outliers, Resonance>;

namespace internal {
template <typename V>
struct AllTermTypes;
template <typename... Ts>
struct AllTermTypes<std::variant<Ts...>> {
  static constexpr bool value = (NoiseTermType<Ts> && ...);
};
}  // namespace internal
static_assert(internal::AllTermTypes<NoiseTerm>::value, "every NoiseTerm alternative is a term");

inline std::string_view TermId(const NoiseTerm& term) {
  return std::visit([](const auto& t) { return std::remove_cvref_t<decltype(t)>::kId; }, term);
}

}  // namespace allanlab::sim
