#pragma once
// Exact equivalent degrees of freedom of the Allan-variance estimator on records of a noise
// model, EDF = 2 E[AVAR_hat]^2 / Var(AVAR_hat) (docs/theory.md §3.1, Isserlis for Gaussian noise).
// Unlike Greenhall & Riley (confidence.h), which models continuous power-law processes, this is
// exact for the discrete records sim::SensorModel generates (docs/theory.md §3.2 table: the two
// differ at small m), so Monte Carlo error bars and coverage checks should use it.
#include <cstdint>
#include <span>
#include <vector>

#include "estimators/exact_avar_variance.h"
#include "estimators/statistic.h"
#include "sim/avar_theory.h"
#include "sim/sensor_model.h"

namespace allanlab::estimators {

// Moments of AVAR_hat(m) for each m in `ms` (shape.estimator: overlapping OAVAR or
// non-overlapping AVAR, on shape.num_samples rate samples), from the model's Gaussian part
// (sim::SensorModel::GaussianAutocovariance: band-limit included; flicker with stationary
// increments; deterministic terms, harmonics, outliers and quantizers left out). Units of the
// model's rate squared (mean) and to the fourth (variance). An m outside 1 <= m <= N/2 gives
// zero moments. Cost O(N) per m after one autocovariance of N + 2 max(m) lags.
std::vector<AvarMoments> ModelAvarMoments(const sim::SensorModel& model,
                                          std::span<const std::int64_t> ms,
                                          const sim::RecordShape& shape);

// EDF = 2 E^2 / Var for each m (0 where the moments are zero).
std::vector<double> ModelAvarEdf(const sim::SensorModel& model, std::span<const std::int64_t> ms,
                                 const sim::RecordShape& shape);

// Moments of OHVAR_hat(m) on num_samples rate samples, from the model's Gaussian part as above,
// O(N) per m (ExactOhvarMomentsFromVariogram); zero for an m OHVAR does not compute on N samples.
std::vector<AvarMoments> ModelOhvarMoments(const sim::SensorModel& model, std::span<const std::int64_t> ms,
                                           std::int64_t num_samples);

// True for the statistics ModelStatisticMoments covers: AVAR, OAVAR, MVAR, HVAR and OHVAR (their
// estimates are averages of squared stationary filters, exact_quadratic_moments.h). TOTVAR's
// reflected extension and TVAR are not covered.
bool HasExactMoments(Statistic s);

// Moments of the statistic's estimate at each m on num_samples rate samples, from the model's
// Gaussian part as above (the term counts and strides of statistic.h: TermCount, stride m for the
// non-overlapping AVAR and HVAR, 1 otherwise). Zero moments for an m the statistic does not
// compute on that record or a statistic without HasExactMoments. AVAR, OAVAR and OHVAR take the
// O(N) paths above; the others cost O(TermCount x 3m) per m (N = 4096: well under a second for an
// octave grid).
std::vector<AvarMoments> ModelStatisticMoments(const sim::SensorModel& model, Statistic s,
                                               std::span<const std::int64_t> ms,
                                               std::int64_t num_samples);

}  // namespace allanlab::estimators
