#pragma once
// A deliberately broken estimator, for proving that the regression check (`allanlab validate`)
// catches a small error: a test builds the experiments with a fault (MakeExperiment's argument,
// ValidateCommandOptions::fault) and expects the tables to be reported as moved. Every other
// caller uses the default, the identity, under which the drivers compute exactly what they would
// without it (x * 1.0 == x).
namespace allanlab::experiments {

struct InjectedFault {
  // Multiplies every Allan-family estimate the experiment drivers take (avar_bias,
  // avar_error_bars, seed_paper, coefficient_recovery, record_length), before anything is read
  // or fitted from it.
  double avar_scale = 1.0;
  // Multiplies every coefficient the drivers read or fit (slope method, WLS, log-WLS, GLS; the
  // seed paper's N and B readings); reported sigmas are left alone.
  double coefficient_scale = 1.0;
};

}  // namespace allanlab::experiments
