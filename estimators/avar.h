#pragma once
// One entry point for an Allan-family curve with confidence intervals:
//   statistic values (allan_family.h) -> noise identification per tau -> EDF -> chi-square CI.
#include <span>

#include "estimators/avar_summary.h"

namespace allanlab::estimators {

// Returns summary->ok. Bad options, too few samples or non-finite data give ok = false and a
// message; taus without enough terms are listed in summary->dropped with the reason.
bool ComputeAvar(const AvarOptions& options, std::span<const double> data, AvarSummary* summary);

}  // namespace allanlab::estimators
