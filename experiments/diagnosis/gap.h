#pragma once
// Standardised residuals of a record against a model, the gap metrics (docs/theory.md §6.2; "How far it
// shrinks": chi2, fraction inside the 95 % band, largest |z|) and the gap regions.
//
// Each residual is turned into an equivalent normal deviate z = Phi^{-1}(P) of its tail
// probability under the model, so every view speaks the same language:
//   exact (OAVAR): OAVAR_hat nu / E ~ chi2_nu with nu = 2 E^2 / Var the exact EDF (docs/theory.md §3.1),
//     the log-domain chi-square that stays honest at few terms;
//   Monte Carlo: (x - mean) / (sd sqrt(1 + 1/n)) ~ Student t_{n-1} for n simulated records (the
//     prediction interval of one more draw; exact for Gaussian statistics, and logs of
//     variances are close to Gaussian).
// Multiplicity: the record is flagged when any |z| over all views exceeds the Bonferroni level
// Phi^{-1}(1 - alpha / (2 M)), M the number of points in all views, so a record drawn from the
// model is flagged with probability <= alpha whatever the correlation between taus (the taus of
// one curve are strongly correlated, so the real rate is below alpha).
#include <limits>
#include <span>
#include <string>
#include <vector>

#include "experiments/diagnosis/record_views.h"

namespace allanlab::experiments {

double ZFromChiSquare(double observed, double expected, double edf);
double ZFromEnvelope(double observed, double mean, double sd, int trials);
// The halves view, ln(OAVAR_first / OAVAR_second): each half's OAVAR is ~ E chi2_nu / nu, so the
// log ratio is ln F(nu, nu) about its centre, whose tails are far heavier than a normal's at the
// few EDF of the long taus (nu = 2: logistic, 9 x the normal tail at the Bonferroni level of a
// record). nu is the one whose ln F variance 2 psi'(nu/2) matches the envelope's sd (inflated by
// sqrt(1 + 1/trials) for the prediction of one more draw), and z comes from the F tails, or from
// ZFromEnvelope (Student: the sd's own uncertainty at few trials) when that is smaller in |z|.
double ZFromLogRatioEnvelope(double observed, double mean, double sd, int trials);
// The same law without an envelope: ln F(edf, edf) (two independent estimates of one variance,
// each ~ chi2_edf / edf; gaussian_views.h).
double ZFromLogRatio(double observed, double edf);
// The same with estimates of unequal EDF: `observed` is ln(O_first / O_second) less
// ln(E_first / E_second), which is ln F(edf_first, edf_second).
double ZFromLogRatio(double observed, double edf_first, double edf_second);
// The dynamic view without an envelope: ln(max / min) of `count` independent estimates of one
// variance, each ~ chi2_edf / edf (gaussian_views.h); z from the range's own tails.
double ZFromLogRange(double observed, double edf, int count);
// The same for independent estimates of unequal means and EDF, each ~ E_w chi2_nu_w / nu_w
// (`log_means`: ln E_w; `edfs`: nu_w; a warm-up drift raises the first windows' means,
// warmup_drift_views.h).
double ZFromLogRangeOfUnequal(double observed, std::span<const double> log_means, std::span<const double> edfs);
// The views of a variance estimate's log (hadamard: ln OHVAR; psd: ln of a band of the Welch
// PSD): each estimate is ~ E chi2_nu / nu, whose log has a long lower tail at few EDF (the last
// hadamard taus, nu ~ 2-5: at nu = 2 the normal reading's threshold z = -3.5 is crossed by 1
// record in 160, not the 1 in 4300 it stands for, and records drawn from the baseline were
// flagged there, the record below the model). nu is the one whose
// ln chi2 variance psi'(nu/2) matches the envelope's sd (inflated as above), the envelope's mean
// is taken as E ln(chi2_nu / nu), and z comes from the chi-square tails or from ZFromEnvelope,
// whichever is smaller in |z|.
double ZFromLogVarianceEnvelope(double observed, double mean, double sd, int trials);
// The kurtosis view (excess kurtosis of the block means' increments): for Gaussian noise the
// sample kurtosis of n values is skewed to the right (skewness 0.87 at n = 256, where the normal
// reading of the envelope put records drawn apart from sim/ above the model at its longest tau,
// the fewest blocks). Its law is read as that of n_eff independent normal values, n_eff the one
// whose kurtosis variance matches the envelope's sd (inflated as above; the increments are
// correlated, so n_eff is below the count), centred on the envelope's mean, and z comes from
// the Anscombe-Glynn transform or from ZFromEnvelope, whichever is smaller in |z|.
double ZFromKurtosisEnvelope(double observed, double mean, double sd, int trials);
// The same law without an envelope: the excess kurtosis of n_eff independent normal values
// (gaussian_views.h), by the Anscombe-Glynn transform. NaN for n_eff <= 8.
double ZFromKurtosis(double excess_kurtosis, double effective_count);
// Phi^{-1}(1 - alpha / (2 points)).
double BonferroniThreshold(double alpha, int points);

// Central `probability` range of one estimate OAVAR_hat ~ expected chi2_edf / edf (the exact
// view's distribution above): where a record of the model falls with that probability.
// Precondition: expected > 0, edf > 0, 0 < probability < 1.
struct Band {
  double low = 0.0, high = 0.0;
};
Band ChiSquareBand(double expected, double edf, double probability);

// One view of one record against one model.
struct ViewResiduals {
  View view = View::kOavar;
  std::vector<double> x;         // tau [s] or frequency [Hz]
  std::vector<double> observed;  // the record's statistic (variances in (rad/s)^2, PSD in
                                 // (rad/s)^2/Hz, log ratios and kurtosis as they are)
  std::vector<double> expected;  // the model's typical value on the same scale
  std::vector<double> z;         // NaN where the point has no distribution (skipped)
  // Block-mean views (block_means.h): where the step is [s from the start] (change_point) or the
  // settling's time constant [s] (trend), per point; empty for the other views.
  std::vector<double> time_s;
};

struct GapMetrics {
  int points = 0;             // finite z
  double chi2 = 0.0;          // sum z^2
  double fraction_in_95 = 1.0;  // |z| <= 1.96
  double max_abs_z = 0.0;
};
GapMetrics Metrics(const std::vector<double>& z);
GapMetrics Metrics(const std::vector<ViewResiduals>& views);  // pooled

struct GapRegion {
  View view = View::kOavar;
  double x_min = 0.0, x_max = 0.0;  // contiguous points with |z| > threshold
  double max_abs_z = 0.0;
  double mean_z = 0.0;  // sign: the record above (> 0) or below the model (block-mean views:
                        // the level rises at the step / settles from above)
  double time_s = std::numeric_limits<double>::quiet_NaN();  // the largest |z| point's time_s
};
std::vector<GapRegion> FindGapRegions(const std::vector<ViewResiduals>& views, double threshold);

}  // namespace allanlab::experiments
