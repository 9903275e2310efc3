#pragma once
// The verdict: whether the record departs from the baseline at all (Bonferroni over every point
// of every view), every effect's candidate ranked, the Monte Carlo views for the plausible ones,
// pairs when no single effect closes the gap, and the one named (with the effects the record
// cannot tell from it).
#include "experiments/diagnosis/diagnosis_context.h"

namespace allanlab::experiments::detail {

// Fills s->threshold, regions, significant, candidates, skipped, verdict, verdict_candidate and
// also_consistent from s->before and s->baseline.
void Finish(const Context& ctx, DiagnosisSummary* s);

}  // namespace allanlab::experiments::detail
