#pragma once
// Recipes of independent/ (a generator written apart from sim/ and the fit) that several tests
// draw records from.
#include <numbers>

#include "independent/recipe.h"

namespace allanlab::testing_support {

// A MEMS gyro behind its output filter: N 0.2 deg/sqrt(h), B 3 deg/h, K 4 deg/h/sqrt(h) through a
// second-order 20 Hz low-pass designed by the bilinear transform at 8x the 100 Hz output rate; no
// quantization and no rate ramp.
inline independent::Recipe BandLimitedMemsRecipe() {
  constexpr double kDeg = std::numbers::pi / 180.0;
  independent::Recipe r;
  r.rate_hz = 100.0;
  r.noise.arw_rad_per_sqrt_s = 0.2 * kDeg / 60.0;
  r.noise.flicker_floor_rad_per_s = independent::FlickerFloorFromB(3.0 * kDeg / 3600.0);
  r.noise.rrw_rad_per_s_per_sqrt_s = 4.0 * kDeg / 3600.0 / 60.0;
  r.low_pass.design = independent::LowPassDesign::kSecondOrderBilinear;
  r.low_pass.cutoff_hz = 20.0;
  r.low_pass.oversampling = 8;
  return r;
}

}  // namespace allanlab::testing_support
