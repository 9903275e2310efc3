#pragma once
// Bias instability (IEEE Std 952, coefficient B): flicker (1/f) rate noise synthesised by the
// Kasdin-Walter fractional-difference filter with alpha = 1, y = (1 - z^-1)^{-1/2} w, by FFT
// convolution from a zero initial state (Kasdin & Walter 1992; docs/theory.md §2.5.1).
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "sim/avar_theory.h"
#include "sim/flicker_stream_cache.h"
#include "sim/term_common.h"

namespace allanlab::sim {

struct FlickerNoise {
  static constexpr std::string_view kId = "bias_instability";
  static constexpr SignalPath kPath = SignalPath::kHeld;

  // B in rad/s (IEEE 952: ADEV floor = sqrt(2 ln2 / pi) B = 0.6643 B). With the Kasdin filter the
  // innovation std equals B, whatever tau0 (one-sided PSD h_{-1} = B^2 / pi).
  double bias_instability_rad_per_s = 0.0;

  bool IsValid(std::string* why) const;
  // y_n = sum_{k<=n} h_k w_{n-k}, h_0 = 1, h_k = h_{k-1} (k - 1/2) / k, w ~ N(0, B^2);
  // y_{-1} = 0 (zero initial state), so the record has the finite-record deficit of docs/theory.md §2.5.3.
  void AddTo(Engine& engine, double tau0_s, std::span<double> rate_rad_per_s) const;
  // Doubles a work buffer needs for SynthesizeInPlace of n samples.
  static std::size_t WorkSize(std::size_t n);
  // Writes (not adds) the n samples AddTo would add into work[0..n), using all of `work`
  // (size >= WorkSize(n)) as FFT space: a caller that keeps the record in `work` needs no second
  // record-sized buffer (this halves simulate's peak memory).
  void SynthesizeInPlace(Engine& engine, std::size_t n, std::span<double> work) const;
  // The same, the unit record taken from (or kept in) `cache` under `stream_seed`, the seed word
  // `engine` was made from: the same bits whether it was kept or not.
  void SynthesizeInPlace(Engine& engine, std::size_t n, std::span<double> work, FlickerStreamCache* cache,
                         std::uint64_t stream_seed) const;
  // When `cache` keeps the unit record of (stream_seed, n): writes the n samples SynthesizeInPlace
  // would into out[0..n) (the same bits) and returns true, with no FFT work space; else false
  // (out untouched).
  bool WriteKept(std::size_t n, std::span<double> out, const FlickerStreamCache& cache, std::uint64_t stream_seed) const;
  // Generalised autocovariance R(k) = -(2 B^2 / pi) sum_{i=1}^{k} 1/(2i - 1) (stationary
  // increments, i.e. without the start-up transient).
  void FillAutocovariance(double tau0_s, std::span<double> r) const;
  // Exact E[AVAR_hat(m)] for the generated record of shape.num_samples samples, including the
  // +44 % excess at m = 1 and the finite-record deficit at large m (docs/theory.md §2.5.2, §2.5.3). Overlapping:
  // O(log N) per m (kasdin_finite_record.h); non-overlapping: the O(N) direct sum.
  double ExpectedAvar(std::int64_t m, double tau0_s, const RecordShape& shape) const;
  // Stationary-increment value (no finite-record deficit).
  double StationaryAvar(std::int64_t m) const;
  // IEEE 952 floor: (2 ln2 / pi) B^2.
  double AsymptoticAvar(double tau_s) const;
};

// sum_{i=1}^{k} 1/(2i - 1) summed in long double in order and rounded to double, k = 0..n-1 (at
// least n values): FillAutocovariance's sums, computed once per process and extended on demand.
// Thread-safe; the returned vector is never modified. nullptr for n beyond 2^22 (not kept).
std::shared_ptr<const std::vector<double>> OddHarmonicSums(std::size_t n);

// Kasdin-Walter coefficients h_0..h_{n-1} for alpha = 1.
std::vector<double> KasdinCoefficients(std::int64_t n);
// Running sums S(v) = sum_{k<=v} p_k.
std::vector<double> CumulativeSum(std::span<const double> p);

}  // namespace allanlab::sim
