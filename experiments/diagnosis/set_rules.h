#pragma once
// The rules of forward selection for a set verdict (docs/theory.md §6.4): which single candidates
// a set may add, and whether an added member earns its place. verdict.cc grows the sets.
#include <cstddef>
#include <string>
#include <vector>

#include "experiments/diagnosis/diagnose.h"

namespace allanlab::experiments::detail {

// Whether `e` is one of `members` or Allan-equivalent to one (effect.h AllanEquivalents).
bool Clashes(const std::vector<EffectInstance>& members, Effect e);

// The single candidates of `s` a set may add (indices into s.candidates): those with a positive
// score (the better of the exact-view and all-view scores), the best kPoolSize effects, each with
// its Allan-equivalent in the same slot (a set takes at most one of the pair: Clashes).
// Why both members of a pair: alone, their scores differ for reasons a set's other members take
// over. On the MTi-G record a telegraph outscored the Gauss-Markov process (6912 against 568) by
// absorbing some of the spikes; beside the spikes' own member the Gauss-Markov process closed
// every view (|z| <= 2.0) and the telegraph did not earn its place.
inline constexpr std::size_t kPoolSize = 5;
std::vector<std::size_t> SetPool(const DiagnosisSummary& s);

// Whether `next` (`current` plus one effect) earns its place, with `margin` the relative chi2 fall
// asked (DiagnoseOptions::set_margin) and `threshold` the record's |z| threshold:
//  * the held-out chi2 falls to at most (1 - margin) of `heldout_before` (current's, scored on
//    next's half and views) minus the added effect's 2k, over all the held-out views or over
//    those of them the added effect shows in (its registry views; per view from
//    `heldout_before_residuals` and next.heldout_residuals);
//  * on some view the added effect shows in where the record departs from `baseline` and the
//    current set still departs, the record's chi2 falls by the margin (the effect explains part
//    of the record's gap by something it is known by, not a departure the other members' refit
//    made: a quantizer's refit that moves the trend view over the threshold does not call for a
//    warm-up drift);
//  * no view within the threshold under `current` leaves it.
// Why the held-out fall may be read in the added effect's own views: a member already in the set
// can leave a held-out chi2 that no later member could lower, and that swamps the added one's. On
// the MTi-G record, spikes whose count differs between the halves left 726 in the held-out
// kurtosis, halves and dynamic views; a Gauss-Markov process added to them took every view of the
// whole record within |z| 2, yet the held-out total fell only to 611, short of the margin (its own
// views: 401 -> 313).
// *step: what the member adds (held-out before and after; the own views' too when those decided).
// *why: the first rule failed, with its numbers.
bool EarnsItsPlace(double margin, double threshold, const ModelGap& baseline, const CandidateResult& current,
                   const CandidateResult& next, const GapMetrics& heldout_before,
                   const std::vector<ViewResiduals>& heldout_before_residuals, CandidateResult::Step* step,
                   std::string* why);

}  // namespace allanlab::experiments::detail
