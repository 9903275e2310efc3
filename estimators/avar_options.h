#pragma once
// Options of one Allan-family computation (estimators/avar.h): the statistic, the taus, the
// input and how intervals are made, with documented defaults.
#include <cstdint>
#include <string>

#include "common/sample_clock.h"
#include "estimators/statistic.h"
#include "estimators/tau_grid.h"

namespace allanlab::estimators {

enum class InputKind {
  kRate,   // rate (frequency) samples, e.g. deg/s
  kAngle,  // angle (phase) samples: N + 1 angles make N rates; rate = diff(angle) / tau0
};

enum class ConfidenceMethod {
  kNone,
  kSimple,          // seed paper / IEEE 952: sigma(delta)/sigma = 1/sqrt(2(K-1)), K clusters
  kGreenhallRiley,  // EDF by Greenhall & Riley (2003), SP 1065 for TOTVAR; chi-square interval
                    // (as Stable32 and allantools: the noise type identified at each tau alone)
  // `allanlab avar`'s default. EDF measured on the record where its own differences are
  // numerous enough (record_edf.h: AVAR, OAVAR, HVAR, OHVAR at short taus, free of the sampling
  // model the Greenhall-Riley EDF assumes), elsewhere Greenhall & Riley at a noise type that, at taus with
  // fewer than kSteadyIdentificationAverages m-averages, stays the shorter tau's unless the
  // identification departs from it by more than one step, and does not rise into phase noise
  // (a lag-1 ACF from 32 averages has a standard error of ~0.35 in alpha: 7 % of white records
  // were read as phase noise at m = N/32, whose EDF is 2-4 times too large). Chi-square interval.
  kAuto,
};

// Below this many m-averages kAuto keeps the shorter tau's noise type unless the identification
// is more than one step away from it.
inline constexpr std::int64_t kSteadyIdentificationAverages = 128;

struct AvarOptions {
  Statistic statistic = Statistic::kAllanOverlapping;
  TauGridOptions taus;
  SampleClock sample_clock;      // tau0 (default 1 s), valid
  InputKind input = InputKind::kRate;
  ConfidenceMethod confidence_method = ConfidenceMethod::kGreenhallRiley;
  double confidence = 0.683;     // two-sided level of the interval, in (0, 1)
  // Fewest terms (differences averaged) a tau must have to be reported; fewer => dropped.
  std::int64_t min_terms = 1;
  // Noise exponent alpha for the EDF: identified per tau when unset (alpha_fixed = false).
  bool alpha_fixed = false;
  int alpha = 0;  // S_y(f) ~ f^alpha, in {-2, -1, 0, 1, 2} (rate: white = 0, flicker = -1, ...)
  // Cost bound of the identification, for curves whose EDFs only need the noise type roughly
  // (`allanlab fit`: its GLS weights come from the covariance model, the EDFs only seed the
  // pilot fit). 0: every m-average of the record. Otherwise, at taus with more averages than
  // this, alpha is identified from the middle this-many of them, a contiguous stretch (so the
  // lag-1 ACF still pairs neighbouring averages); the ACF's standard error is then about
  // 1/sqrt(count), e.g. 0.006 at 32768, far inside the alpha bands. At least 30 when set.
  std::int64_t identification_max_averages = 0;

  bool IsValid(std::string* why) const;
};

// The bound the commands use (avar, fit, diagnose): the ACF's standard error 0.006 keeps the
// identified alpha the full record's on independent records of every noise type
// (tests/estimators/capped_identification_stat_test.cc), and identification then costs O(taus)
// rather than O(N).
inline constexpr std::int64_t kIdentificationMaxAverages = std::int64_t{1} << 15;

}  // namespace allanlab::estimators
