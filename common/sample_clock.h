#pragma once
// The sample clock of a uniformly sampled record: its rate and its period, both fixed when the
// clock is made from whichever of the two the source gives (a rate from a command line or a sensor
// spec, a period from a time column or an Allan curve). Code reads the one it needs and never
// converts one into the other itself, so a record's tau0 has one value wherever it is used.
#include <cmath>

namespace allanlab {

class SampleClock {
 public:
  // 1 Hz, 1 s.
  constexpr SampleClock() = default;

  static constexpr SampleClock FromRateHz(double rate_hz) { return SampleClock(rate_hz, 1.0 / rate_hz); }
  static constexpr SampleClock FromPeriodS(double period_s) { return SampleClock(1.0 / period_s, period_s); }

  constexpr double rate_hz() const { return rate_hz_; }
  constexpr double period_s() const { return period_s_; }   // tau0

  // Finite and positive (a clock made from 0, a negative or a non-finite value is not).
  bool IsValid() const { return std::isfinite(rate_hz_) && std::isfinite(period_s_) && rate_hz_ > 0.0 && period_s_ > 0.0; }

  friend constexpr bool operator==(const SampleClock&, const SampleClock&) = default;

 private:
  constexpr SampleClock(double rate_hz, double period_s) : rate_hz_(rate_hz), period_s_(period_s) {}
  double rate_hz_ = 1.0;
  double period_s_ = 1.0;
};

}  // namespace allanlab
