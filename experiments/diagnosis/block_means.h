#pragma once
// The block-mean views: the record's rate level over time against the model's block-mean
// covariance (docs/theory.md §6.7). They see a bias step or a warm-up drift directly, in the time
// domain, where the Allan curve can hide it (a free rate random walk or ramp absorbs the long-tau
// rise a step makes), and place it in time.
//
// For B blocks of m = floor(N / B) samples, u_b the mean of block b of the record less the model's
// deterministic path (its bias steps and warm-up drifts), the differences d_i = u_{i+1} - u_i
// (i < B - 1) are Gaussian with the Toeplitz covariance C of §6.7, exact for the model's random
// part from its generalised autocovariance (band-limit and quantizers included); a rate ramp's
// unknown sign enters as a random slope of variance R^2. With C = L L^T and w = C^{-1} d, a
// regressor h (the d-signature of a unit step, or of a unit exponential settling) has the GLS
// likelihood-ratio statistic T_h = (h . w)^2 / (h^T C^{-1} h) ~ chi2_1 under the model.
//   change_point: the largest T_h over steps at every block edge and every mid-block point;
//                 located at that split [s from the start]
//   trend:        the largest T_h over exponential settlings A e^{-t / tw} from the start, tw on
//                 a log grid from 2 m tau0 to 4 N tau0 (the longest is a linear trend); located by
//                 its time constant tw
// Null distribution: the maximum over the family from `kBlockMeanNullDraws` fixed draws of
// w = L^{-T} e, e ~ N(0, I) (the statistic's exact law under the Gaussian model, by Monte Carlo):
// p = (1 + exceedances) / (draws + 1), and beyond the 20th largest draw the tail extrapolated with
// the chi2_1 tail's shape; z = Phi^{-1}(1 - p/2) with the sign of the fitted size (> 0: the rate
// rises at the step / the settling starts above the final level). So each point has
// P(|z| > t) ~ 2 (1 - Phi(t)) under the model and the record's Bonferroni threshold over every
// point of every view (gap.h) keeps its false-alarm rate <= alpha with these views in it.
// Measured on independent records against their true model: docs/theory.md §6.7.
#include <cstdint>
#include <span>
#include <vector>

#include "experiments/diagnosis/gap.h"
#include "sim/sensor_model.h"

namespace allanlab::experiments {

inline constexpr int kBlockMeanNullDraws = 2000;

// The block counts for a record of n samples: 64, 32, 16 (block lengths ascending), where each
// block keeps >= 16 samples.
std::vector<int> BlockMeanCounts(std::int64_t n);

// The model's covariance of adjacent block-mean differences for blocks of m samples: c[k] =
// Cov(d_i, d_{i+k}) for k = 0 .. blocks - 2 [(rad/s)^2] (docs/theory.md §6.7, eq. 6.7.3), its random
// part only (deterministic terms, harmonics left out; outliers as white noise of variance p a^2).
// Precondition: model.IsValid(), m >= 1, blocks >= 3.
std::vector<double> BlockDifferenceCovariance(const sim::SensorModel& model, std::int64_t m, int blocks);

// The standard deviation of each block mean about the mean of all `blocks` block means of m
// samples, under the model's random part as the block-mean views see it (docs/theory.md §6.7: its
// structure function D, a ramp as a random slope; deterministic terms and harmonics left out):
// Var(u_b - mean u) = (1/B) sum_j D(|b - j|) - (1/(2 B^2)) sum_{i,j} D(|i - j|), exact for Gaussian
// noise with stationary increments; larger at the ends when the noise wanders (K, R, flicker).
// [rad/s]. Precondition: model.IsValid(), m >= 1, blocks >= 2.
std::vector<double> BlockMeanDeviationSd(const sim::SensorModel& model, std::int64_t m, int blocks);

// The record against the model in both block-mean views: x the block length [s], observed the
// fitted size (a step [rad/s], a settling's amplitude [rad/s]), expected its standard deviation
// under the model, z as above, time_s where the step is [s from the start] (change_point) or the
// settling's time constant tw [s] (trend). Points whose covariance is singular are NaN. With
// `rate_random_walk_bound` > 0 (K fitted to this record, the largest K the fit allows: its 95 %
// upper end, or its upper limit when the fit left K out) [rad/s/sqrt(s)], the change-point
// statistic profiles K out between 0 and the larger of that bound and the model's K
// (profiled_step.h), against that statistic's own null law at that largest K.
void BlockMeanResiduals(std::span<const double> rate_rad_per_s, double sample_period_s,
                        std::span<const int> block_counts, const sim::SensorModel& model,
                        double rate_random_walk_bound, ViewResiduals* change_point, ViewResiduals* trend);

// Means of `blocks` equal blocks of floor(x.size() / blocks) samples (the rest left out).
// Precondition: 1 <= blocks <= x.size().
std::vector<double> BlockMeans(std::span<const double> x, int blocks);

// The model's deterministic path (its bias steps and warm-up drifts, placed in time), sample by
// sample over n samples; empty when it has none.
std::vector<double> DeterministicPath(const sim::SensorModel& model, std::int64_t n);

// The change-point view's most significant point beyond `threshold` in `views`: where it places
// the step [s from the start] and its block length [s]; false (outputs untouched) when none.
bool LocatedStep(const std::vector<ViewResiduals>& views, double threshold, double* time_s, double* block_s);

}  // namespace allanlab::experiments
