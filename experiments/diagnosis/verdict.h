#pragma once
// The verdict: whether the record departs from the baseline at all (Bonferroni over every point
// of every view), every effect's candidate ranked, the Monte Carlo views for the plausible ones,
// sets grown by forward selection when no single effect closes the gap (docs/theory.md §6.4), and
// the one named, or the one explaining most of the gap (§6.6) (with the effects the record
// cannot tell from it).
#include "experiments/diagnosis/diagnosis_context.h"

namespace allanlab::experiments::detail {

// Fills s->threshold, regions, significant, candidates, skipped, verdict, verdict_candidate and
// also_consistent from s->before and s->baseline.
void Finish(const Context& ctx, DiagnosisSummary* s);

}  // namespace allanlab::experiments::detail
