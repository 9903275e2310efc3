#pragma once
// The statistic values alone (no intervals): exact, O(N) per tau with prefix sums of the
// mean-removed record (a bias of 1e4 x the noise level changes nothing beyond 1e-9 relative).
// Definitions: NIST SP 1065 (Riley 2008) eqs. for AVAR, OAVAR, MVAR, HVAR, OHVAR, TOTVAR, TVAR,
// with rate samples as fractional frequency and angle as phase.
#include <span>

#include "estimators/avar_summary.h"

namespace allanlab::estimators {

// Fills summary->points (value, terms; alpha/edf/ci left zero) and summary->dropped.
// `rate` are rate samples (angle input already differenced by the caller).
bool ComputeStatisticValues(const AvarOptions& options, std::span<const double> rate,
                            AvarSummary* summary);

// Differences angle samples into rates: rate_k = (angle_{k+1} - angle_k) / tau0.
std::vector<double> AngleToRate(std::span<const double> angle, double tau0_s);

}  // namespace allanlab::estimators
