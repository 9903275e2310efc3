#pragma once
// The distribution of each view's statistics under a sensor model, for records of the real
// record's length and rate, and the standardised residuals of a record against it (gap.h).
//   OAVAR: exact. Mean from sim::SensorModel::ExpectedAvar (every term, deterministic ones
//     included), EDF 2 E^2 / Var with Var of the Gaussian part by Isserlis
//     (estimators/exact_edf.h): cheap, O(N) per tau.
//   Other views: for a Gaussian model, or one plus a warm-up drift, from theory
//     (gaussian_views.h, warmup_drift_views.h); else Monte Carlo of the
//     model (fixed seed, `trials` records, OpenMP across trials;
//     deterministic for any thread count: trial t always uses (seed, t) and the moments are summed
//     in trial order). The records are drawn with sim::GenerateOptions that keep their law and
//     cut their cost (white noise behind a first-order band-limit per output period; one flicker
//     record per trial shared by the models of one record).
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "experiments/diagnosis/gap.h"
#include "experiments/diagnosis/gaussian_views.h"
#include "experiments/diagnosis/record_views.h"
#include "sim/sensor_model.h"

namespace allanlab::experiments {

struct OavarTheory {
  std::vector<double> mean;  // E[OAVAR_hat(m)] (rad/s)^2, per layout.oavar_m
  std::vector<double> edf;
};
// Precondition: model.IsValid(), m <= N/2.
OavarTheory ExactOavar(const sim::SensorModel& model, std::span<const std::int64_t> ms,
                       std::int64_t num_samples);

struct ViewEnvelope {
  int trials = 0;      // successful simulated records
  ViewValues mean, sd;  // per view and point, on the views' (log) scale
};
// Returns false with *why when the model is invalid or no simulated record gave values. Views
// not in `wanted` are left NaN; the others do not depend on which are wanted.
// The flicker record every model's envelope on one record shares per trial (docs/theory.md §6.1):
// drawn from `seed`'s stream, synthesised once and kept in `cache`.
struct SharedFlicker {
  sim::FlickerStreamCache* cache = nullptr;
  std::uint64_t seed = 0;
};

// `shared_flicker` (may be null: each model its own flicker stream from `seed`).
bool SimulateEnvelope(const sim::SensorModel& model, const ViewLayout& layout, int trials,
                      std::uint64_t seed, ViewEnvelope* envelope, std::string* why,
                      const ViewSet& wanted = EveryView(), const SharedFlicker* shared_flicker = nullptr);

// Residuals of `observed` (ComputeViews of the record) against the model: the OAVAR view from
// `theory`, the others from `gaussian` when given (GaussianViewZ), else from `envelope` (views
// absent from the envelope, or with fewer than 3 trials, are left out), the views in `wanted`
// only, in View order.
std::vector<ViewResiduals> Residuals(const ViewLayout& layout, const ViewValues& observed,
                                     const OavarTheory& theory, const ViewEnvelope* envelope,
                                     const ViewSet& wanted = EveryView(), const GaussianViewTheory* gaussian = nullptr);

}  // namespace allanlab::experiments
