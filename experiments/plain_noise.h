#pragma once
// Power-law rate records made here, apart from sim/: other random numbers (the C++ standard
// library's mt19937_64 and normal_distribution, not sim/'s Boost ones), other discretizations and
// a flicker of another construction, each with its exact expected Allan variance in closed form
// or from its autocovariance. Unit scale: the expectations are for the records as generated, and
// coverage and bias do not depend on the level.
//   white          iid N(0, 1): AVAR(m) = 1/m
//   flicker        the sum of 47 stationary AR(1) processes of unit variance with correlation
//                  times 2^(j/2) samples, j = -6..40: a 1/f spectrum from 2^-3 to 2^20 samples
//                  (equal power per octave of corner frequency); AVAR from the autocovariance
//   random walk    y_k = sum_{i <= k} w_i, point-sampled: AVAR(m) = (2 m^2 + 1) / (6 m)
//   random walk, averaged   each sample the mean of a Wiener process over its interval (the
//                  exact joint law of the increment and the interval mean): AVAR(m) = m / 3
//   quantization   the difference of iid N(0, 1) angles, y_k = theta_k - theta_{k-1} (white
//                  phase noise, as a quantizer's error): AVAR(m) = 3 / m^2
//                  (docs/theory.md §2.1 with Q = 1, tau0 = 1); not in PlainNoises()
#include <cstdint>
#include <string>
#include <vector>

namespace allanlab::experiments {

enum class PlainNoise { kWhite, kFlicker, kRandomWalk, kRandomWalkAveraged, kQuantization };

// The four rate noises (not quantization), in table order, and a label for tables ("white", "flicker", "random walk",
// "random walk (averaged)").
const std::vector<PlainNoise>& PlainNoises();
std::string PlainNoiseLabel(PlainNoise noise);
// Short id for column names: "white", "flicker", "rw", "rw_averaged".
std::string PlainNoiseId(PlainNoise noise);

// n samples; a pure function of (noise, n, seed, stream).
std::vector<double> GeneratePlain(PlainNoise noise, std::int64_t n, std::uint64_t seed,
                                  std::uint64_t stream);

// The exact expectation of the overlapping (and non-overlapping) Allan variance at averaging
// factor m >= 1 of GeneratePlain's records.
double PlainExpectedAvar(PlainNoise noise, std::int64_t m);

// The autocovariance r(k), k >= 0, of GeneratePlain's samples: generalised (up to a constant)
// for the point-sampled random walk (-k/2); for the filters of experiments/family_expectation.h.
// Throws std::invalid_argument for the averaged random walk (not needed there).
double PlainAutocovariance(PlainNoise noise, std::int64_t k);

}  // namespace allanlab::experiments
