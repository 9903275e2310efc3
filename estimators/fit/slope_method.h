#pragma once
// The graphical slope method exactly as sensor papers use it (IEEE Std 952 Annex C; Mikheev et
// al. 2021; MATLAB's allanvar example): straight lines of fixed slope on the log-log ADEV plot,
// read at fixed taus, and the bias instability from the curve's minimum:
//   N = sigma(1 s) on the -1/2 line     (N[deg/sqrt(h)] = sigma(1 s)[deg/h] / 60)
//   Q = sigma(sqrt(3) s) on the -1 line (AVAR = 3 Q^2 / tau^2)
//   K = sigma(3 s) on the +1/2 line     (AVAR = K^2 tau / 3)
//   R = sigma(sqrt(2) s) on the +1 line (AVAR = R^2 tau^2 / 2)
//   B = min sigma / sqrt(2 ln2 / pi)    (biased: sqrt(B^2 + 2.617 N K) with N, B, K present,
//                                        docs/theory.md §4.2)
// Kept as the baseline whose bias the experiments measure, not as a recommended estimator.
#include <array>
#include <string>

#include "estimators/fit/avar_curve.h"
#include "estimators/fit/noise_coefficient.h"

namespace allanlab::estimators {

struct SlopeMethodOptions {
  // A tau belongs to a slope region when its local log-log ADEV slope is within this of the
  // region's slope. 0.15 separates -1/2 from 0 and +1/2 with margin.
  double slope_tolerance = 0.15;
};

struct SlopeReading {
  bool found = false;
  double value_si = 0.0;     // coefficient in SI (see noise_coefficient.h)
  double tau_lo_s = 0.0;     // the region the line was fitted on
  double tau_hi_s = 0.0;
  int points = 0;
  std::string note;          // why not found, or caveats (extrapolated, minimum at the end)
};

struct SlopeMethodResult {
  std::array<SlopeReading, 5> readings;  // indexed by Coefficient
  const SlopeReading& at(Coefficient c) const { return readings[static_cast<int>(c)]; }
};

// Precondition: curve.IsValid().
SlopeMethodResult ReadSlopes(const AvarCurve& curve, const SlopeMethodOptions& options = {});

}  // namespace allanlab::estimators
