#pragma once
// One recording of the blind diagnosis benchmark ("Proof on data whose effect is
// withheld"): which sensor, how long, how fast, which effect (or none: a control) and how strong,
// all drawn from (seed, index) alone.
//
// The sensor is a shipped preset reduced to its IEEE 952 terms (Q, N, B, K, R): the presets'
// band-limits and output quantizers are themselves effects of the vocabulary (bandwidth,
// rate_quantization), so a control with them would not be a control.
//
// Strength, one scale for every effect: the expected peak OAVAR gap z,
//   z(tau) = |ln(E_full(tau) / E_fit(tau))| * sqrt(nu(tau) / 2),   strength = max over tau,
// where E_full is the exact expected OAVAR of the recording's model (sim::SensorModel::
// ExpectedAvar; quantizers approximated), E_fit the best the baseline can do with it (WLS fit of
// Q, N, B, K, R to E_full, no term selection: the share of the effect the baseline absorbs is not
// a gap), and nu the exact EDF of the baseline model (docs/theory.md §3.1). ln(OAVAR_hat) has standard
// deviation ~ sqrt(2 / nu), so z is the number of standard deviations by which the record's curve
// is expected to leave the fitted model at that tau: 1 is invisible, the diagnosis flags beyond its
// Bonferroni level (~3.6), 10 is clearly visible. Effects whose signature the baseline absorbs in
// the Allan view get the expected z of the view that does see them, and the strength is the largest:
//   outliers, rate and angle quantization (the white AVAR of spikes and of a fine quantizer is
//     absorbed by N and Q): the expected excess kurtosis of the first differences over its null sd
//     sqrt(24 / N); spikes +-a with probability p per sample: 2 p a^4 (1 - 3 p) / V^2, V =
//     2 E_full(m=1); quantization errors uniform over the LSB (Sheppard's regime): rate
//     -2.4 (q^2/12)^2 / V^2, angle -21.6 (q^2/12)^2 / (tau0^4 V^2);
//   bias_step, exponential_drift (a step's AVAR is ~ s^2 tau / 3T, the K term's shape): the halves
//     view, |ln(E_first / E_second)| sqrt(nu_half / 4) at octave m <= N/16, the second half's
//     effect shifted by T/2 (candidate_estimate.h ShiftEffect).
// The effect's expected tau range: the taus where z(tau) reaches the diagnosis's Bonferroni level
// for the record's view points (`threshold_z`); empty when the effect is not expected to be seen
// in the OAVAR view.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "experiments/diagnosis/effect.h"
#include "sim/sensor_model.h"

namespace allanlab::experiments {

struct BenchmarkDrawOptions {
  std::vector<std::string> presets = {"consumer_mems", "fog",           "mg25_mems",
                                      "rlg",           "tactical_mems", "tg100"};
  double min_duration_s = 1800.0, max_duration_s = 10800.0;  // log-uniform
  double min_rate_hz = 100.0, max_rate_hz = 1000.0;          // log-uniform
  // Cap on N = duration * rate (the rate is lowered to fit; 3 h at 100 Hz always fits): the
  // CPU budget of the benchmark, as diagnose costs ~40 s CPU per 1e6 samples with an effect.
  std::int64_t max_samples = 1080000;
  double control_fraction = 0.4;  // recordings with no effect
  // Of the effect recordings: strength classes drawn with these weights, the target strength
  // log-uniform inside [0.3, 2) weak, [2, 10) borderline, [10, 100] clear.
  double weak_weight = 0.2, borderline_weight = 0.2, clear_weight = 0.6;
  bool IsValid(std::string* why) const;
};

// The strength class boundaries on the peak gap z scale.
inline constexpr double kBorderlineStrength = 2.0;
inline constexpr double kClearStrength = 10.0;
// "control", "weak" (< 2), "borderline" (< 10), "clear".
std::string StrengthClass(bool control, double strength_z);

struct BenchmarkCase {
  int index = 0;
  std::string preset;
  SampleClock sample_clock;
  std::int64_t num_samples = 0;
  double duration_s() const { return static_cast<double>(num_samples) / sample_clock.rate_hz(); }
  sim::SensorModel base;                 // the preset's IEEE 952 terms on sample_clock
  std::optional<EffectInstance> effect;  // nullopt: a control
  sim::SensorModel model;                // base + effect
  double target_z = 0.0;      // drawn strength (0 for controls)
  double strength_z = 0.0;    // achieved (a parameter bound can stop the solve short)
  double relative_peak = 0.0;  // max |E_full / E_fit - 1| over the taus
  double peak_tau_s = 0.0;    // tau of the largest OAVAR gap z (0: none)
  double oavar_z = 0.0;       // the OAVAR gap z at its peak
  double kurtosis_z = 0.0;    // outliers and quantizers
  double halves_z = 0.0;      // bias_step and exponential_drift
  double halves_peak_tau_s = 0.0;
  std::string strength_class;
  // What the table's params column shows when the parameters are not the effect's own (effect.h),
  // as for the independent generator's recordings (independent_case.h); empty: effect->params.
  std::string params_text;
  std::vector<double> tau_s, gap_z;  // the OAVAR gap z per tau (10 per decade, m <= N/2)
  // Taus where gap_z >= threshold_z; {0, 0} when none.
  std::pair<double, double> ExpectedTauRange(double threshold_z) const;
};

// Deterministic in (seed, index). Returns false with *why when the options are invalid or the
// model cannot be built.
bool DrawBenchmarkCase(const BenchmarkDrawOptions& options, std::uint64_t seed, int index,
                       BenchmarkCase* c, std::string* why);

// The strength of `effect` added to `base` for a record of n samples (fills strength_z,
// relative_peak, peak_tau_s, kurtosis_z, tau_s and gap_z of *c; c->model is set to base + effect).
bool MeasureStrength(const sim::SensorModel& base, const std::optional<EffectInstance>& effect,
                     std::int64_t n, BenchmarkCase* c, std::string* why);

}  // namespace allanlab::experiments
