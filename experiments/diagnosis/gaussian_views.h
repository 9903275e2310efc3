#pragma once
// The distributions of the views beyond OAVAR under a Gaussian model, from theory instead of
// the Monte Carlo envelope (envelope.h), as the OAVAR view's is (docs/theory.md §6.1).
//   hadamard: exact. E[OHVAR_hat(m)] and its EDF 2 E^2 / Var (Isserlis) from the model's phase
//     variogram (estimators::ExactOhvarMomentsFromVariogram, O(N) per m); z from the chi-square,
//     as for OAVAR.
//   kurtosis: asymptotic. The increments D_i of the block means of m samples are the Allan
//     differences at lags i m, so their autocorrelation rho(h) follows from the same variogram.
//     For a Gaussian sequence the excess kurtosis is, to first order, the mean of the fourth
//     Hermite polynomial of the standardised values, whose covariance at lag h is 24 rho(h)^4
//     (Mehler): Var = (24 / n) sum_{|h|<n} (1 - |h|/n) rho(h)^4, the variance of n_eff =
//     n / sum(...) independent values. z from the Anscombe-Glynn transform at n_eff (gap.h).
//   halves: ln(OAVAR_first / OAVAR_second) ~ ln F(nu, nu), nu the exact EDF of OAVAR(m) on N/2
//     samples (the halves taken as independent: for a random walk or flicker they are positively
//     correlated at long m, which narrows the ratio, so this reading is conservative there).
//   dynamic: ln(max / min) over 8 windows, the range of 8 independent ln(chi2_nu / nu), nu the
//     exact EDF of OAVAR(m) on N/8 samples (gap.h ZFromLogRange; conservative likewise).
//   psd: the mean of each band of the Welch PSD exactly (each bin's E|X_b|^2 = sum_l R(l)
//     Gamma_b(l), Gamma_b the autocorrelation of the demeaned Hann window at bin b), its EDF
//     by Welch's rule for a locally flat spectrum: 2 K b_n / (f_seg f_bin) for K segments of
//     50 % overlap (f_seg = 1 + 2 (1/36)(K-1)/K: overlapping Hann segments correlate 1/6 in
//     amplitude) and b_n bins per band (f_bin = 1 + 2 (4/9)(b_n-1)/b_n + 2 (1/36)(b_n-2)/b_n:
//     Hann's neighbouring bins correlate 2/3, the next 1/6); the first band (bin 1 alone, where
//     the spectrum is steepest and the segment mean reaches) has its exact EDF, the segments'
//     correlation and X's non-circularity included.
// A Gaussian model: every term Gaussian (white, flicker, random walk, Gauss-Markov, resonance, Q)
// or cancelled by both views (the rate ramp: OHVAR's third difference and the increments' own
// mean remove it), band-limit included, no quantizer but a fine one (IsGaussianModel). Harmonics,
// telegraphs, steps, drifts and outliers are not Gaussian, nor is a coarse quantizer's error:
// their views stay Monte Carlo, but for one warm-up drift on a Gaussian model, whose path is
// known (warmup_drift_views.h). Flicker enters with stationary increments, as a sensor running
// before the record started has it (the simulated records start the Kasdin filter from rest,
// which at the last hadamard taus lowers the mean by a few per cent).
// Why not the Monte Carlo envelope: at the last points of both views (a few EDF; the fewest
// blocks) 30 simulated records pin neither the statistic's centre nor its spread, and the
// statistics are skewed. Controls drawn apart from sim/ were flagged there in 6 of 240 (hadamard
// below the model 3 times, kurtosis above it 3 times, where the level allows about 0.12 per
// point), and none of the six with the envelope from 300 records.
#include <cstdint>
#include <vector>

#include "experiments/diagnosis/record_views.h"
#include "sim/sensor_model.h"

namespace allanlab::experiments {

struct GaussianViewTheory {
  std::vector<double> hadamard_mean;  // E[OHVAR_hat(m)] (rad/s)^2, per layout.hadamard_m
  std::vector<double> hadamard_edf;
  std::vector<double> kurtosis_effective_count;  // n_eff, per layout.kurtosis_m (NaN: no blocks)
  std::vector<double> halves_edf;                // per layout.halves_m
  std::vector<double> dynamic_edf;               // per layout.dynamic_m
  std::vector<double> psd_mean, psd_edf;         // per layout.psd_bands: (rad/s)^2/Hz, EDF
  // With a warm-up drift (warmup_drift_views.h); empty without one. Halves: ln(E_first /
  // E_second) and the second half's EDF (halves_edf is the first's). Dynamic: per point, each
  // window's ln E and EDF (empty at a point the drift leaves alike). Kurtosis: the shift of the
  // mean and the ratio of the sds.
  std::vector<double> halves_log_offset, halves_edf_second;
  std::vector<std::vector<double>> dynamic_log_means, dynamic_edfs;
  std::vector<double> kurtosis_shift, kurtosis_sd_ratio;
  bool empty() const { return hadamard_mean.empty(); }
};

// z of point i of a view beyond OAVAR (not change_point or trend) from its observed value (on the
// view's scale: logs for hadamard and psd) under theory `t`; *expected: the view's value the
// model puts there (hadamard and psd: E, not its log).
double GaussianViewZ(View view, const GaussianViewTheory& t, double observed, std::size_t i, double* expected);

// The share of the output's first differences' variance that its quantizers' errors make
// (0 without a quantizer), from their exact second moments (sim::SensorModel::
// GaussianAutocovariance).
double QuantizerShareOfDifferences(const sim::SensorModel& model);

// True when the model's law is Gaussian in the sense above for records of `num_samples` samples.
// A fine output quantizer counts as Gaussian: when its error is a small share s of the first
// differences (s <= 0.02 at 1e6 samples, s <= 0.05 at 2.5e4), the signal crosses many LSBs per
// sample, the error is white, uniform and uncorrelated with the signal (Widrow & Kollar,
// "Quantization Noise", 2008: its correlation from one sample to the next, exp(-2 pi^2 D / lsb^2)
// with D the signal's one-sample increment variance, is below 1e-20 there), its second moments
// are in GaussianAutocovariance, and what is left of its law, the uniform's excess kurtosis -1.2
// weighted by s^2, moves the kurtosis view by at most a tenth of its standard deviation
// sqrt(24 / N) (and the other views' variances by less). A coarse one stays Monte Carlo. (An
// ADIS16405's 0.05 deg/s LSB on its 0.4 deg/s of white noise per sample at 100 Hz is fine:
// s = 0.002 as a rate quantizer, 0.006 as an angle one.)
bool IsGaussianModel(const sim::SensorModel& model, std::int64_t num_samples);

// Empty unless IsGaussianModel(model), or the model is a Gaussian one plus one warm-up drift
// (warmup_drift_views.h), and every hadamard point has positive moments.
GaussianViewTheory ExactGaussianViews(const sim::SensorModel& model, const ViewLayout& layout);

}  // namespace allanlab::experiments
