#pragma once
// Independent test records: Generate makes one from a recipe (recipe.h: the chain and its
// order), Inject adds a recipe's effects to a recording someone else made (a real sensor's).
//
//   independent::Recipe r;
//   r.rate_hz = 100;
//   r.noise.arw_rad_per_sqrt_s = 1e-4;
//   r.noise.flicker_floor_rad_per_s = 5e-6;
//   r.bias_step = independent::BiasStep{2e-5, 1800.0};
//   std::vector<double> y = independent::Generate(r, 720000, /*seed=*/7, /*stream=*/0);
//   double e = independent::ExpectedOavar(r, /*m=*/100, 720000);  // allan_forms.h
//
// Deterministic: the samples are a pure function of (recipe, n, seed, stream) on any thread count;
// each component draws from its own random stream, so adding an effect does not change the noise
// the others produce. Throws std::invalid_argument when !recipe.IsValid(n).
#include <cstdint>
#include <span>
#include <vector>

#include "independent/recipe.h"

namespace allanlab::independent {

// n rate samples (rad/s) at recipe.rate_hz.
std::vector<double> Generate(const Recipe& recipe, std::int64_t n, std::uint64_t seed, std::uint64_t stream);

// Adds the recipe's terms to `rate` (rad/s, at recipe.rate_hz) in place, in the chain's order:
// the recording takes the place of the wideband noise (its own noise is kept; recipe.noise's white
// noise is added too); a low-pass filters the recording and the added white noise at the output
// rate (oversampling treated as 1: the recording's internal samples do not exist); then the slow
// terms and effects, the quantizer and the spikes.
void Inject(const Recipe& recipe, std::uint64_t seed, std::uint64_t stream, std::span<double> rate);

}  // namespace allanlab::independent
