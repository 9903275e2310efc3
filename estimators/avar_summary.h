#pragma once
// Result of one Allan-family computation: what was asked (the options) and what was used.
#include <cstdint>
#include <string>
#include <vector>

#include "estimators/avar_options.h"

namespace allanlab::estimators {

struct AvarPoint {
  std::int64_t m = 0;        // averaging factor
  double tau_s = 0.0;        // m * tau0
  double value = 0.0;        // the variance, in (input units)^2 ((angle units)^2 for kTime)
  std::int64_t terms = 0;    // number of squared differences averaged
  int alpha = 0;             // noise exponent used for the EDF
  // false when fixed by the options, when identification failed, or when the shorter tau's
  // exponent is held at few clusters (kAuto, <= kDistributionIntervalMaxClusters)
  bool alpha_identified = false;
  double edf = 0.0;          // equivalent degrees of freedom (0 when no interval)
  bool edf_from_record = false;  // kAuto: the EDF was measured on the record (record_edf.h)
  // kAuto at <= kDistributionIntervalMaxClusters clusters: the interval comes from the estimate's
  // distribution at alpha (estimate_distribution.h), not from chi-square(edf).
  bool ci_from_distribution = false;
  double ci_low = 0.0;       // interval for the variance at options.confidence
  double ci_high = 0.0;
};

struct DroppedTau {
  double tau_s = 0.0;
  std::int64_t m = 0;
  std::string reason;
};

struct AvarSummary {
  AvarOptions options;
  std::int64_t num_samples = 0;  // rate samples used (angles - 1 for angle input)
  std::vector<AvarPoint> points;
  std::vector<DroppedTau> dropped;
  bool ok = false;
  std::string message;  // why !ok, or notes (e.g. "2 taus dropped")
};

}  // namespace allanlab::estimators
