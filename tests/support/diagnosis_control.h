#pragma once
// The control recording model of the diagnose tests: white rate noise (ARW 1e-4 rad/s/sqrt(s))
// plus rate random walk (1e-6 rad/s^2/sqrt(s)) at 100 Hz, no unmodelled effect, so that every
// view (OAVAR, Hadamard, halves, dynamic, PSD, kurtosis) has something to compare.
#include "sim/sensor_model.h"

namespace allanlab::testing {

inline sim::SensorModel DiagnosisControlModel() {
  sim::SensorModel model;
  model.sample_clock = SampleClock::FromRateHz(100.0);
  sim::WhiteRateNoise white;
  white.arw_rad_per_sqrt_s = 1e-4;
  sim::RandomWalkRate walk;
  walk.rrw_rad_per_s_per_sqrt_s = 1e-6;
  model.terms = {white, walk};
  return model;
}

}  // namespace allanlab::testing
