#pragma once
// The statistic values alone (no intervals): exact, O(N) per tau with prefix sums of the record
// about a level near its mean (estimators/phase_integral.h: a bias of 1e4 x the noise level
// changes nothing beyond 1e-9 relative).
// Definitions: NIST SP 1065 (Riley 2008) eqs. for AVAR, OAVAR, MVAR, HVAR, OHVAR, TOTVAR, TVAR,
// with rate samples as fractional frequency and angle as phase.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <utility>

#include "estimators/avar_summary.h"
#include "estimators/phase_checkpoints.h"

namespace allanlab::estimators {

// Fills summary->points (value, terms; alpha/edf/ci left zero) and summary->dropped.
// `rate` are rate samples (angle input already differenced by the caller). Returns summary->ok:
// false, with the reason in summary->message, for invalid options, fewer than 3 samples, a
// non-finite sample (its index is named) or when no tau has enough terms (all are in dropped).
// Largest m per statistic and the term counts: statistic.h (MaxAveragingFactor, TermCount).
// Cost: O(N) per tau; the overlapping Allan and Hadamard statistics share cache-blocked passes
// (an octave OAVAR curve of 1e8 samples takes a few ns per sample). Extra memory: N + 1 doubles
// for the phase, plus up to N doubles of work space for MVAR and TVAR; except for OAVAR and OHVAR
// on grids whose long lags sit on the cache tiers (octave; difference_sums.h), which this
// overload computes from ~N/256 bytes of checkpoints and ~3 MB of windows, the same bits, since
// it keeps no phase for the caller.
bool ComputeStatisticValues(const AvarOptions& options, std::span<const double> rate,
                            AvarSummary* summary);

// Scratch memory of ComputeStatisticValues, kept between calls. Touching fresh pages costs more
// than the whole computation on long records (measured 5-12 ns per sample in our VM, against a
// few ns for the octave OAVAR curve itself), so a loop over many records (Monte Carlo trials)
// should keep one per thread. After a successful call, Phase(N + 1) holds that call's integrated
// record x (x_0 = 0, x_{k+1} = x_k + y_k - reference, reference a level near the mean), which
// noise identification reuses; other contents between calls are unspecified.
class AllanFamilyWorkspace {
 public:
  // `size` doubles, not initialised; the storage grows and is never shrunk.
  std::span<double> Phase(std::size_t size) {
    return adopted_.size() == size ? adopted_ : phase_.Get(size);
  }
  // Phase(storage.size()) is `storage` from now on. When the rate given to ComputeStatisticValues
  // is storage.subspan(1), the record is integrated in place (x_{k+1} replaces rate_k, each read
  // before it is written) and the rate is consumed.
  void AdoptPhase(std::span<double> storage) { adopted_ = storage; }
  std::span<double> Scratch(std::size_t size) { return scratch_.Get(size); }
  // From now on the overlapping statistics, on grids the checkpoint pass takes (difference_sums.h:
  // the octave grid), keep checkpoints of the integrated record (phase_checkpoints.h) instead of
  // the record itself: no N-sized phase is touched, and the pass is shared with a helper thread
  // on long records. After such a call Checkpoints() is non-null (and refers to the rate given),
  // and Phase() is not filled; after any other call it is null.
  void KeepCheckpointsOnly() { checkpoints_only_ = true; }
  bool checkpoints_only() const { return checkpoints_only_; }
  const PhaseCheckpoints* Checkpoints() const { return has_checkpoints_ ? &checkpoints_ : nullptr; }
  // Checkpoints already integrated (complete) from the rate the next call is given, about that
  // rate's ReferenceLevel: that call uses them instead of integrating again.
  void AdoptCheckpoints(PhaseCheckpoints checkpoints) {
    checkpoints_only_ = true;
    adopted_checkpoints_ = true;
    checkpoints_ = std::move(checkpoints);
  }
  // The checkpoints of `rate` about `reference`: the adopted ones when they are those, else built.
  const PhaseCheckpoints& SetCheckpoints(std::span<const double> rate, double reference) {
    const bool same = adopted_checkpoints_ && checkpoints_.complete() && checkpoints_.rate().data() == rate.data() &&
                      checkpoints_.rate().size() == rate.size() && checkpoints_.reference() == reference;
    if (!same) checkpoints_ = PhaseCheckpoints(rate, reference);
    adopted_checkpoints_ = false;
    has_checkpoints_ = true;
    return checkpoints_;
  }
  void ClearCheckpoints() { has_checkpoints_ = false; }
  // Called by the next call once Phase(N + 1) holds the whole integrated record, with the lags
  // being computed and the rest of the pass (which only reads the phase): the hook must run that
  // rest once before returning, and may meanwhile read the phase (e.g. identify the noise at
  // every tau in another thread). Not called when the pass keeps checkpoints or fails early.
  using PhaseReadyHook =
      std::function<void(std::span<const std::int64_t> lags, const std::function<void()>& rest)>;
  void SetPhaseReady(PhaseReadyHook hook) { phase_ready_ = std::move(hook); }
  const PhaseReadyHook& phase_ready() const { return phase_ready_; }

 private:
  class Buffer {
   public:
    std::span<double> Get(std::size_t size);

   private:
    std::unique_ptr<double[]> data_;
    std::size_t capacity_ = 0;
  };
  Buffer phase_, scratch_;
  std::span<double> adopted_;
  bool checkpoints_only_ = false;
  bool has_checkpoints_ = false;
  bool adopted_checkpoints_ = false;
  PhaseCheckpoints checkpoints_;
  PhaseReadyHook phase_ready_;
};

// As above, with the work space supplied by the caller (null: as above, no phase kept).
bool ComputeStatisticValues(const AvarOptions& options, std::span<const double> rate,
                            AvarSummary* summary, AllanFamilyWorkspace* workspace);

// Differences angle samples into rates: rate_k = (angle_{k+1} - angle_k) / tau0.
std::vector<double> AngleToRate(std::span<const double> angle, double tau0_s);

}  // namespace allanlab::estimators
