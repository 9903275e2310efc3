#pragma once
// Effects with nonlinear parameters that a fit adds on top of the linear IEEE 952 sum model
// (sum_i c_i^2 S_i(tau), noise_coefficient.h): a Gauss-Markov process (sigma, Tc), a harmonic
// (Omega0, f0), the band-limit (fc, for a given filter order) and, later, any other sim effect.
// Generic on purpose: the sim-to-real diagnosis (experiments/diagnosis/) fits candidate effects through the same
// interface. A term knows nothing about fitting; it says
//   - what its parameters are (names, SI and datasheet units, bounds, scale),
//   - where a fit should start, from the curve and the residual AVAR a baseline fit leaves,
//   - how to add itself to a sim::SensorModel with given parameter values.
// The last point makes sim/ the one place that knows each effect's exact expected AVAR
// (SensorModel::ExpectedAvar, band-limit and finite record included) and lets a parametric
// bootstrap simulate the fitted model (SensorModel::Generate) with no second implementation.
// The band-limit is not additive (it filters every held and wideband term), which is why a term
// edits the model rather than returning a curve of its own.
// Stable interface: ids and members are only ever added, never renamed.
#include <limits>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "estimators/fit/avar_curve.h"
#include "sim/band_limit.h"
#include "sim/sensor_model.h"

namespace allanlab::estimators {

struct ParameterSpec {
  std::string name;            // "sigma", "Tc", "Omega0", "f0", "fc"
  std::string si_unit;         // "rad/s", "s", "Hz"
  std::string datasheet_unit;  // the JSON units of `allanlab fit`: "deg/h", "s", "Hz"
  double si_per_datasheet = 1.0;  // value_si = value_datasheet * si_per_datasheet
  // Admissible SI range. Bounds may depend on the curve (see Bounds()); these are the static ones.
  double lower_si = 0.0;
  double upper_si = std::numeric_limits<double>::infinity();
  // Fitted as ln(value) (positive scale parameters: amplitudes, times, frequencies). All the
  // present terms' parameters are; a future signed parameter sets false.
  bool log_scale = true;
};

class ParametricTerm {
 public:
  virtual ~ParametricTerm() = default;

  // Stable effect id: the sim term id for additive terms ("gauss_markov", "harmonic"), or
  // "bandwidth" for the band-limit.
  virtual std::string_view id() const = 0;
  // The CLI name in `allanlab fit --terms`: "GM", "H", "BW" (first order), "BW2" (Butterworth).
  virtual std::string_view short_name() const = 0;
  virtual const std::vector<ParameterSpec>& parameters() const = 0;
  // Bounds on this curve (e.g. Tc within the curve's tau span, f0 below Nyquist); defaults to
  // the static ones. lower[i] <= upper[i], both finite for log-scale parameters after this call.
  virtual void Bounds(const AvarCurve& curve, std::vector<double>* lower_si,
                      std::vector<double>* upper_si) const;
  // Where the fit starts: from the curve, `residual_avar` = data - baseline (same taus, may be
  // negative) and `model_without` = the baseline as a model (the linear terms at their baseline
  // values). Returns false with why when the curve shows nothing this term could explain; the
  // term is then left out of the fit.
  virtual bool InitialGuess(const AvarCurve& curve, std::span<const double> residual_avar,
                            const sim::SensorModel& model_without, std::vector<double>* params_si,
                            std::string* why) const = 0;
  // Adds the effect with these parameters (SI, in parameters() order) to the model.
  virtual void ApplyTo(std::span<const double> params_si, sim::SensorModel* model) const = 0;
  // True when the term multiplies into the other terms (band-limit) rather than adding to them.
  virtual bool modifies_other_terms() const { return false; }
};

// First-order Gauss-Markov rate noise, sim::GaussMarkov: parameters sigma (rad/s; datasheet
// deg/h) and Tc (s). Its AVAR peaks at tau ~ 1.89 Tc at 0.381 sigma^2.
std::unique_ptr<ParametricTerm> MakeGaussMarkovTerm();
// Random telegraph signal, sim::RandomTelegraph: parameters a (rad/s; deg/h) and dwell (mean
// dwell, s). Same AVAR as a Gauss-Markov process with sigma = a, Tc = dwell/2.
std::unique_ptr<ParametricTerm> MakeRandomTelegraphTerm();
// Random-phase sinusoid, sim::Harmonic: parameters Omega0 (peak, rad/s; deg/h) and f0 (Hz).
// AVAR = Omega0^2 (sin^2(x)/x)^2, x = pi f0 tau (exact point-sampled form in sim/).
std::unique_ptr<ParametricTerm> MakeHarmonicTerm();
// The band-limit (sim::BandLimit) of the given filter kind, output sampling and oversampling L:
// parameter fc (Hz), bounded by 0.45 L fs. With averaged output the long-tau white level is the
// input's (N keeps its meaning whatever fc); point sampling folds the filter's tail above fs/2
// back into the band (the fitted N is then the density before the chain). Precondition: L in
// [1, 256].
std::unique_ptr<ParametricTerm> MakeBandLimitTerm(sim::LowPassKind kind,
                                                  sim::OutputSampling sampling = sim::OutputSampling::kPoint,
                                                  int oversampling = 8);

// The band-limit's screen (what MakeBandLimitTerm's InitialGuess does): on a cutoff grid from
// fs/100 to the term's upper bound, the baseline's terms (`without`) band-limited by this filter
// and each rescaled (non-negative weighted least squares, weights nu / (2 AVAR^2)) fit to the
// curve. Returns false when no cutoff beats the unfiltered terms; else the best cutoff and its
// weighted SSE relative to the unfiltered terms' (< 1), so filters can be ranked cheaply.
bool ScreenBandLimit(sim::LowPassKind kind, sim::OutputSampling sampling, int oversampling,
                     const AvarCurve& curve, const sim::SensorModel& without, double* cutoff_hz,
                     double* sse_ratio);

// The band-limit term's highest cutoff [Hz]: 0.45 of the rate its filter runs at (oversampling x
// the output rate), 0.3 for a box kind (which must stay at least one internal sample long).
double BandLimitMaxCutoffHz(sim::LowPassKind kind, int oversampling, double output_period_s);

// Narrowband resonance, sim::Resonance: parameters sigma (rad/s; deg/h), f0 (Hz) and zeta
// (damping ratio). f0 is bounded below the output Nyquist frequency (a line above it is not a
// resonance the record can locate), zeta by [1e-3, 0.95].
// The resonance term's damping range: a fit at the floor has found a line narrower than it can
// describe (over the record, a sinusoid).
inline constexpr double kResonanceMinDamping = 1e-3;
inline constexpr double kResonanceMaxDamping = 0.95;
std::unique_ptr<ParametricTerm> MakeResonanceTerm();

// By CLI name ("GM", "RTS", "H", "RES", "BW", "BW2") or id ("gauss_markov", "random_telegraph",
// "harmonic", "resonance", "bandwidth" = first order); band-limits with point sampling, L = 8; nullptr if
// unknown.
std::unique_ptr<ParametricTerm> MakeParametricTerm(std::string_view name);

}  // namespace allanlab::estimators
