#pragma once
// The integrated record x of a rate record (phase_integral.h: x_0 = 0, x_{k+1} = x_k + y_k -
// reference) without an N-sized array: one integration pass keeps x at every kStride-th index,
// and any stretch of x is rebuilt from the checkpoint at or before it. Pieces of the integral
// that start at multiples of 8 have the bits of one integration of the whole record
// (ContinueIntegral), so every rebuilt value is the stored phase's, bit for bit.
//
// Why: N + 1 fresh doubles cost more to touch than the octave Allan curve costs to compute
// (allan_family.h), and a read-only record (a mapped file) cannot host its own integral. The
// checkpoints take N / 8 bytes; what reads x (the Allan pass, noise identification, the record
// EDF) rebuilds only the stretches it needs, in cache-sized buffers.
#include <cstdint>
#include <span>
#include <vector>

namespace allanlab::estimators {

class PhaseCheckpoints {
 public:
  // x at every kStride-th index: the identification at m >= kStride and the long lags of the
  // Allan pass read their x straight from here.
  static constexpr std::int64_t kStride = 64;

  PhaseCheckpoints() = default;
  // Integrates rate about reference once (the rate must outlive this object).
  PhaseCheckpoints(std::span<const double> rate, double reference);
  // The same pass left to the caller: IntegrateUpTo as the samples become available (a reader
  // that checks them block by block integrates each block while it is in cache).
  struct Deferred {};
  PhaseCheckpoints(std::span<const double> rate, double reference, Deferred);
  // Continues the pass through sample `upto` - 1 (rounded down to a multiple of kStride unless
  // upto >= N); the bits do not depend on the steps taken.
  void IntegrateUpTo(std::int64_t upto);
  bool complete() const { return done_ == n_; }

  std::int64_t size() const { return n_; }  // N: x_0 .. x_N exist
  std::span<const double> rate() const { return rate_; }
  double reference() const { return reference_; }
  // x_N (once complete): not finite when a sample is not, or the running sum overflows.
  double Last() const { return last_; }
  // x_k for k a multiple of kStride, k <= N.
  double At(std::int64_t k) const { return x_[static_cast<std::size_t>(k / kStride)]; }

  // out[i] = x_{lo + i}, i < out.size(), lo + out.size() - 1 <= N.
  void Rebuild(std::int64_t lo, std::span<double> out) const;
  // out[i] = x_{first + i m}, i < out.size(): from the checkpoints when m and first are
  // multiples of kStride, else rebuilt piece by piece.
  void Decimate(std::int64_t first, std::int64_t m, std::span<double> out) const;

 private:
  // x_a for a a multiple of 8, from the checkpoint at or before it.
  double At8(std::int64_t a) const;
  // group[j] = x_{a + j} for j <= min(8, N - a), given x_a (a a multiple of 8).
  void Group(std::int64_t a, double x_a, double* group) const;

  std::span<const double> rate_;
  double reference_ = 0.0;
  std::int64_t n_ = 0;
  double last_ = 0.0;
  std::int64_t done_ = 0;  // the pass has integrated x_0 .. x_done_
  std::vector<double> x_;  // x_{k kStride}
};

}  // namespace allanlab::estimators
