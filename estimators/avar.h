#pragma once
// One entry point for an Allan-family curve with confidence intervals:
//   statistic values (allan_family.h) -> noise identification per tau -> EDF -> chi-square CI.
#include <cstddef>
#include <span>
#include <vector>

#include "estimators/avar_summary.h"
#include "estimators/confidence.h"
#include "estimators/phase_checkpoints.h"

namespace allanlab::estimators {

// Returns summary->ok. Bad options, too few samples or non-finite data give ok = false and a
// message; taus without enough terms are listed in summary->dropped with the reason.
bool ComputeAvar(const AvarOptions& options, std::span<const double> data, AvarSummary* summary);

// The same for a record the caller gives up: the integrated record is built in its storage
// instead of a second record-sized buffer (on 1e8 samples: 800 MB less and ~0.5 s of page
// faults spared). storage[0] is a spare slot (its value is ignored) and the samples follow it,
// so that no sample has to move: rate input is integrated in place, angle input differenced
// first. storage must hold at least the spare slot; its contents are unspecified afterwards.
// Same results as ComputeAvar, except that a non-finite running sum is reported by position only.
bool ComputeAvarOnStorage(const AvarOptions& options, std::span<double> storage,
                          AvarSummary* summary);

// ComputeAvar with the integrated record built in `phase` (data.size() + 1 doubles) where the
// pass keeps one (rate input below kCheckpointMinSamples; else `phase` is not used): memory the
// caller has had prepared meanwhile, e.g. its pages faulted in by another thread while this one
// waits for nothing (app/input/record_curve.cc). The same results.
bool ComputeAvar(const AvarOptions& options, std::span<const double> data, AvarSummary* summary,
                 std::span<double> phase);

// From this many samples on, ComputeAvar keeps checkpoints of the integrated record rather than
// the record (AllanFamilyWorkspace::KeepCheckpointsOnly): the checkpoints are re-read from the
// samples for every pass (about six, each a pass over the samples' memory), while a stored
// integral costs its fresh pages once; below ~256 MB those cost less than the passes, above it the
// kernel's zeroing of them (and the compaction that finds huge pages for them on a busy machine:
// seconds of system time at 1e8 samples) costs more.
inline constexpr std::size_t kCheckpointMinSamples = std::size_t{1} << 25;

// ComputeAvar for rate input whose integration pass was already made: `checkpoints` complete,
// from the rate samples about their ReferenceLevel (phase_integral.h), e.g. integrated by a reader
// block by block as it checked them. Same results as ComputeAvar(options, checkpoints.rate()).
bool ComputeAvarFromCheckpoints(const AvarOptions& options, PhaseCheckpoints checkpoints, AvarSummary* summary);

// ComputeAvarOnStorage for a vector of samples alone: the spare slot is inserted in front (one
// move of the record; a reader that can leave the slot itself should, see record_reader.h).
bool ComputeAvarInPlace(const AvarOptions& options, std::vector<double>* record,
                        AvarSummary* summary);

// The interval of a computed point at `confidence`, by the rule ComputeAvar applied at
// options.confidence: [v edf / chi2_{1-p}, v edf / chi2_p] (confidence.h), or, where
// point.ci_from_distribution, [v / q_{1-p}, v / q_p] with q the quantiles of the estimate's own
// distribution at point.alpha (estimate_distribution.h). [0, inf) when the point has no interval.
Interval PointInterval(const AvarSummary& summary, const AvarPoint& point, double confidence);

}  // namespace allanlab::estimators
