#include "estimators/fit/bounded_threshold.h"

#include <cmath>

#include <boost/math/distributions/chi_squared.hpp>
#include <boost/math/distributions/normal.hpp>

namespace allanlab::estimators {

double BoundedLikelihoodRatioThreshold(double level, double distance_sd) {
  const boost::math::normal standard;
  const double far = boost::math::quantile(boost::math::chi_squared(1.0), level);
  const double s = distance_sd;
  if (s * s >= far) return far;  // the acceptance region does not reach z < 0
  if (s <= 0.0) {
    const double z = boost::math::quantile(standard, level);
    return z * z;
  }
  // The acceptance probability rises with c; at c = s^2 it is P(|z| <= s) < level, at c = far it
  // is at least level: bisect between.
  auto accepted = [&](double c) {
    return boost::math::cdf(standard, std::sqrt(c)) - boost::math::cdf(standard, -(s * s + c) / (2.0 * s));
  };
  double lo = s * s, hi = far;
  for (int i = 0; i < 60 && hi - lo > 1e-9 * far; ++i) {
    const double mid = 0.5 * (lo + hi);
    (accepted(mid) < level ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace allanlab::estimators
