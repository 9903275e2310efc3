#pragma once
// The baseline a diagnosis measures the record against: the linear IEEE 952 terms fitted to the
// record's overlapping Allan curve (GLS, WLS when GLS fails or degenerates), and that fit as a
// sensor model.
#include <cstddef>
#include <string>

#include "estimators/fit/avar_curve.h"
#include "estimators/fit/fit_avar_model.h"
#include "experiments/diagnosis/diagnose.h"
#include "sim/sensor_model.h"

namespace allanlab::experiments::detail {

// The curve a record or a table gives: fewer taus than this cannot carry a baseline and a
// candidate.
inline constexpr std::size_t kMinTaus = 8;

// The fitted linear terms (those with a positive value) as a sensor model at `sample_rate_hz`.
sim::SensorModel LinearModel(const estimators::FitSummary& fit, double sample_rate_hz);

// The asked terms (options.terms) fitted to `curve`; false when neither GLS nor WLS fits. A WLS
// fallback is named in *note (may be null).
bool FitLinear(const DiagnoseOptions& options, const estimators::AvarCurve& curve,
               estimators::FitSummary* fit, std::string* note);

}  // namespace allanlab::experiments::detail
