#pragma once
// The acceptance band of a coverage count: the counts a calibrated interval gives with
// probability at least 1 - false_fail when each of `trials` records holds the truth with
// probability `nominal` (Binomial(trials, nominal)). Two-sided, false_fail / 2 in each tail; lower
// only (a conservative limit allowed): false_fail below, `trials` above.
#include <boost/math/distributions/binomial.hpp>

namespace allanlab::testing_support {

struct CountBand {
  int lo = 0;  // the smallest count with P(X < lo) <= tail
  int hi = 0;  // the largest count with P(X > hi) <= tail
};

inline CountBand CoverageBand(int trials, double nominal, double false_fail, bool lower_only) {
  const boost::math::binomial b(trials, nominal);
  const double tail = lower_only ? false_fail : false_fail / 2.0;
  CountBand band{0, trials};
  while (band.lo < trials && boost::math::cdf(b, band.lo) <= tail) ++band.lo;
  while (!lower_only && band.hi > 0 && boost::math::cdf(boost::math::complement(b, band.hi - 1)) <= tail) --band.hi;
  return band;
}

}  // namespace allanlab::testing_support
