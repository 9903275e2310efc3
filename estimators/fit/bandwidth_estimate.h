#pragma once
// The sensor's bandwidth from the short-tau inflection of the Allan curve (the seed paper's
// indirect method): band-limited white rate noise has its ADEV maximum at tau = 0.301/fc for a
// first-order low-pass (= 1.89 time constants) and 0.468/fc for a 2nd-order Butterworth
// (docs/theory.md §2.9). The seed paper equates the inflection tau with the time constant; it is 1.89
// time constants. The peak is located by a weighted quadratic fit of log ADEV vs log tau around
// the largest short-tau ADEV, with its uncertainty propagated from the EDFs.
#include <string>

#include "estimators/fit/avar_curve.h"

namespace allanlab::estimators {

struct BandwidthEstimate {
  bool found = false;
  double peak_tau_s = 0.0;        // tau of the ADEV maximum
  double peak_tau_sigma_s = 0.0;  // its standard uncertainty
  double cutoff_first_order_hz = 0.0, cutoff_first_order_sigma_hz = 0.0;    // 0.301 / tau_peak
  double cutoff_butterworth2_hz = 0.0, cutoff_butterworth2_sigma_hz = 0.0;  // 0.468 / tau_peak
  double time_constant_s = 0.0, time_constant_sigma_s = 0.0;  // first order: tau_peak / 1.8926
  std::string note;  // why not found
};

// Looks for an interior ADEV maximum before the curve's first minimum. Needs at least 5 taus
// around it; EDFs weight the points (equal weights if the curve has none).
BandwidthEstimate EstimateBandwidth(const AvarCurve& curve);

}  // namespace allanlab::estimators
