#pragma once
// Test hooks of `allanlab validate` (issue 5): a deliberately broken estimator, switched on only
// through the environment, so a test can prove that the regression check catches it.
//   ALLANLAB_INJECT_AVAR_SCALE=<f>         multiplies every Allan-family estimate the experiment
//                                          drivers take (avar_bias, avar_error_bars, seed_paper,
//                                          coefficient_recovery, record_length) by f, before
//                                          anything is read or fitted from it
//   ALLANLAB_INJECT_COEFFICIENT_SCALE=<f>  multiplies every coefficient the drivers read or fit
//                                          (slope method, WLS, log-WLS, GLS; the seed paper's N
//                                          and B readings) by f; reported sigmas are left alone
// Each is read once per process; unset, empty, non-numeric or non-positive means 1.
namespace allanlab::experiments {

double InjectedAvarScale();
double InjectedCoefficientScale();

}  // namespace allanlab::experiments
