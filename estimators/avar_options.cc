#include "estimators/avar_options.h"

#include <cmath>
#include <string>

#include "common/number_text.h"

namespace allanlab::estimators {

bool AvarOptions::IsValid(std::string* why) const {
  if (StatisticId(statistic).empty()) {
    *why = "unknown statistic";
    return false;
  }
  if (!taus.IsValid(why)) {
    *why = "tau grid: " + *why;
    return false;
  }
  if (!sample_clock.IsValid()) {
    *why = "sample period must be finite and > 0 s, got " + SignificantDigits(sample_clock.period_s(), 9);
    return false;
  }
  if (input != InputKind::kRate && input != InputKind::kAngle) {
    *why = "unknown input kind";
    return false;
  }
  if (confidence_method != ConfidenceMethod::kNone &&
      confidence_method != ConfidenceMethod::kSimple &&
      confidence_method != ConfidenceMethod::kGreenhallRiley &&
      confidence_method != ConfidenceMethod::kAuto) {
    *why = "unknown confidence method";
    return false;
  }
  // Checked even without an interval: a bad level is a mistake wherever it comes from.
  if (!(confidence > 0.0 && confidence < 1.0)) {
    *why = "confidence level must be in (0, 1), got " + SignificantDigits(confidence, 9);
    return false;
  }
  if (min_terms < 1) {
    *why = "min_terms must be >= 1, got " + std::to_string(min_terms);
    return false;
  }
  if (identification_max_averages != 0 && identification_max_averages < 30) {
    *why = "identification_max_averages must be 0 (all) or >= 30, got " +
           std::to_string(identification_max_averages);
    return false;
  }
  if (alpha_fixed && (alpha < -2 || alpha > 2)) {
    *why = "fixed noise exponent alpha must be in [-2, 2], got " + std::to_string(alpha);
    return false;
  }
  return true;
}

}  // namespace allanlab::estimators
