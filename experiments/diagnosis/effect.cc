#include "experiments/diagnosis/effect.h"

#include <cmath>

#include "estimators/fit/parametric_term.h"
#include "experiments/diagnosis/candidate_estimate.h"

namespace allanlab::experiments {
namespace {

double Param(const EffectInstance& e, const char* name) {
  const auto it = e.params.find(name);
  return it == e.params.end() ? std::nan("") : it->second;
}

// A term of sim/ added to the model after its own validity check.
template <typename Term>
bool AddTerm(Term t, sim::SensorModel* model, std::string* why) {
  if (!t.IsValid(why)) return false;
  model->terms.push_back(t);
  return true;
}

// Replaces a band-limit the model holds (the baseline's first-order fit, or the user's sensor's):
// the candidate is the record's filter, not a second one in series.
bool AddBandwidth(const EffectInstance& e, sim::SensorModel* model, std::string* why) {
  const double order = Param(e, "order");
  if (order != 1.0 && order != 2.0) {
    *why = "bandwidth: order must be 1 or 2";
    return false;
  }
  model->band_limit.kind = order == 1.0 ? sim::LowPassKind::kFirstOrder : sim::LowPassKind::kButterworth2;
  model->band_limit.cutoff_hz = Param(e, "cutoff_hz");
  // Point sampling of the filtered internal signal: the analog chain of sim/band_limit.h.
  model->band_limit.sampling = sim::OutputSampling::kPoint;
  model->band_limit.oversampling = 8;
  if (const auto it = e.params.find("family"); it != e.params.end()) {
    const auto& families = sim::BandLimitFamilies();
    const double index = it->second;
    if (!(index >= 0.0 && index < static_cast<double>(families.size())) || index != std::floor(index)) {
      *why = "bandwidth: family must be an index below " + std::to_string(families.size());
      return false;
    }
    const sim::BandLimitFamily& f = families[static_cast<std::size_t>(index)];
    if (f.order != static_cast<int>(order)) {
      *why = "bandwidth: family " + std::string(f.name) + " is of order " + std::to_string(f.order);
      return false;
    }
    model->band_limit.kind = f.kind;
    model->band_limit.oversampling = f.oversampling;
    model->band_limit.sampling = f.sampling;
  }
  return model->band_limit.IsValid(model->sample_clock.rate_hz(), why);
}

bool AddGaussMarkov(const EffectInstance& e, sim::SensorModel* model, std::string* why) {
  sim::GaussMarkov t;
  t.sigma_rad_per_s = Param(e, "sigma_rad_per_s");
  t.correlation_time_s = Param(e, "correlation_time_s");
  return AddTerm(t, model, why);
}

bool AddRandomTelegraph(const EffectInstance& e, sim::SensorModel* model, std::string* why) {
  sim::RandomTelegraph t;
  t.amplitude_rad_per_s = Param(e, "amplitude_rad_per_s");
  t.mean_dwell_s = Param(e, "mean_dwell_s");
  return AddTerm(t, model, why);
}

bool AddHarmonic(const EffectInstance& e, sim::SensorModel* model, std::string* why) {
  sim::Harmonic t;
  t.amplitude_rad_per_s = Param(e, "amplitude_rad_per_s");
  t.frequency_hz = Param(e, "frequency_hz");
  return AddTerm(t, model, why);
}

bool AddAngleQuantization(const EffectInstance& e, sim::SensorModel* model, std::string* why) {
  sim::AngleQuantizer q;
  q.lsb_rad = Param(e, "lsb_rad");
  if (!q.IsValid(why)) return false;
  model->angle_quantizer = q;
  return true;
}

bool AddRateQuantization(const EffectInstance& e, sim::SensorModel* model, std::string* why) {
  sim::RateQuantizer q;
  q.lsb_rad_per_s = Param(e, "lsb_rad_per_s");
  // Where the record's signal sits on its grid is unknown (a sensor's bias, the wander of B and
  // K): the simulated records draw it per record. With it fixed at 0 an LSB of several times the
  // per-sample noise gave simulated records a different error from the record's (Hadamard and PSD
  // views of the candidate at chi2 700-1800 on 16-24 points, where OAVAR, whose theory already
  // averages over the offset, fitted).
  q.random_offset = true;
  if (const auto it = e.params.find("subtractive_dither"); it != e.params.end()) {
    if (it->second != 0.0 && it->second != 1.0) {
      *why = "rate_quantization: subtractive_dither must be 0 or 1";
      return false;
    }
    q.subtractive_dither = it->second == 1.0;
  }
  if (!q.IsValid(why)) return false;
  model->rate_quantizer = q;
  return true;
}

bool AddExponentialDrift(const EffectInstance& e, sim::SensorModel* model, std::string* why) {
  sim::ExponentialDrift t;
  t.amplitude_rad_per_s = Param(e, "amplitude_rad_per_s");
  t.time_constant_s = Param(e, "time_constant_s");
  return AddTerm(t, model, why);
}

bool AddBiasStep(const EffectInstance& e, sim::SensorModel* model, std::string* why) {
  sim::BiasStep t;
  t.size_rad_per_s = Param(e, "size_rad_per_s");
  t.time_s = Param(e, "time_s");
  return AddTerm(t, model, why);
}

bool AddResonance(const EffectInstance& e, sim::SensorModel* model, std::string* why) {
  sim::Resonance t;
  t.sigma_rad_per_s = Param(e, "sigma_rad_per_s");
  t.frequency_hz = Param(e, "frequency_hz");
  t.damping = Param(e, "damping");
  return AddTerm(t, model, why);
}

bool AddOutliers(const EffectInstance& e, sim::SensorModel* model, std::string* why) {
  sim::Outliers t;
  t.rate_hz = Param(e, "rate_hz");
  t.size_rad_per_s = Param(e, "size_rad_per_s");
  return AddTerm(t, model, why);
}

std::shared_ptr<const estimators::ParametricTerm> GaussMarkovTerm(const EffectInstance&) {
  return estimators::MakeGaussMarkovTerm();
}
std::shared_ptr<const estimators::ParametricTerm> RandomTelegraphTerm(const EffectInstance&) {
  return estimators::MakeRandomTelegraphTerm();
}
std::shared_ptr<const estimators::ParametricTerm> HarmonicTerm(const EffectInstance&) {
  return estimators::MakeHarmonicTerm();
}
std::shared_ptr<const estimators::ParametricTerm> ResonanceTerm(const EffectInstance&) {
  return estimators::MakeResonanceTerm();
}
std::shared_ptr<const estimators::ParametricTerm> BandwidthTerm(const EffectInstance& e) {
  return DiagnosisBandLimitTerm(e);
}

// A warm-up drift seen offset_s later has decayed by exp(-offset / tw).
std::optional<EffectInstance> ShiftDrift(const EffectInstance& e, double offset_s) {
  EffectInstance s = e;
  s.params["amplitude_rad_per_s"] *= std::exp(-offset_s / e.params.at("time_constant_s"));
  return s;
}

// A step seen offset_s later happens offset_s earlier; before the start it no longer acts.
std::optional<EffectInstance> ShiftStep(const EffectInstance& e, double offset_s) {
  EffectInstance s = e;
  s.params["time_s"] -= offset_s;
  if (s.params["time_s"] <= 0.0) return std::nullopt;
  return s;
}

}  // namespace

const std::vector<EffectSpec>& EffectRegistry() {
  using enum View;
  // A telegraph signal of amplitude a and mean dwell T has the autocovariance a^2 e^{-2|t|/T} of a
  // Gauss-Markov process with sigma = a, Tc = T/2 (sim/random_telegraph.h): every second-moment
  // view (Allan, Hadamard, PSD) is the same; the increments' kurtosis is not.
  static const std::vector<EffectSpec> registry = {
      {Effect::kBandwidth, "bandwidth", {"cutoff_hz", "order"}, AddBandwidth, BandwidthStart, false,
       BandwidthTerm, HeldRefit::kRatio, nullptr, {kOavar, kHadamard, kPsd}, {}},
      {Effect::kGaussMarkov, "gauss_markov", {"sigma_rad_per_s", "correlation_time_s"}, AddGaussMarkov,
       GaussMarkovStart, false, GaussMarkovTerm, HeldRefit::kRatio, nullptr, {kOavar, kHadamard, kPsd},
       {{Effect::kRandomTelegraph, "kurtosis"}}},
      {Effect::kRandomTelegraph, "random_telegraph", {"amplitude_rad_per_s", "mean_dwell_s"},
       AddRandomTelegraph, RandomTelegraphStart, false, RandomTelegraphTerm, HeldRefit::kRatio, nullptr,
       {kOavar, kHadamard, kPsd, kKurtosis}, {{Effect::kGaussMarkov, "kurtosis"}}},
      {Effect::kHarmonic, "harmonic", {"amplitude_rad_per_s", "frequency_hz"}, AddHarmonic, HarmonicStart,
       true, HarmonicTerm, HeldRefit::kRatio, nullptr, {kOavar, kHadamard, kPsd}, {}},
      {Effect::kAngleQuantization, "angle_quantization", {"lsb_rad"}, AddAngleQuantization,
       AngleQuantizationStart, true, nullptr, HeldRefit::kSubtractive, nullptr, {kOavar, kPsd, kKurtosis}, {}},
      {Effect::kRateQuantization, "rate_quantization", {"lsb_rad_per_s"}, AddRateQuantization,
       RateQuantizationStart, true, nullptr, HeldRefit::kSubtractive, nullptr, {kOavar, kPsd, kKurtosis}, {}},
      {Effect::kExponentialDrift, "exponential_drift", {"amplitude_rad_per_s", "time_constant_s"},
       AddExponentialDrift, ExponentialDriftStart, true, nullptr, HeldRefit::kJointFit, ShiftDrift,
       {kOavar, kHalves, kDynamic, kChangePoint, kTrend}, {}},
      {Effect::kBiasStep, "bias_step", {"size_rad_per_s", "time_s"}, AddBiasStep, BiasStepStart, true,
       nullptr, HeldRefit::kJointFit, ShiftStep, {kOavar, kHalves, kDynamic, kKurtosis, kChangePoint, kTrend}, {}},
      {Effect::kOutliers, "outliers", {"rate_hz", "size_rad_per_s"}, AddOutliers, OutliersStart, true,
       nullptr, HeldRefit::kJointFit, nullptr, {kOavar, kPsd, kKurtosis}, {}},
      {Effect::kResonance, "resonance", {"sigma_rad_per_s", "frequency_hz", "damping"}, AddResonance,
       ResonanceStart, false, ResonanceTerm, HeldRefit::kRatio, nullptr, {kOavar, kHadamard, kPsd}, {}},
  };
  return registry;
}

const EffectSpec& SpecOf(Effect e) {
  for (const EffectSpec& spec : EffectRegistry()) {
    if (spec.effect == e) return spec;
  }
  return EffectRegistry().front();  // unreachable: the registry covers the enum
}

std::string_view EffectId(Effect e) { return SpecOf(e).id; }

bool ParseEffect(std::string_view id, Effect* e) {
  for (const EffectSpec& spec : EffectRegistry()) {
    if (spec.id == id) {
      *e = spec.effect;
      return true;
    }
  }
  return false;
}

std::vector<std::string> EffectParameterNames(Effect e) { return SpecOf(e).params; }

std::string FilterFamilyName(const EffectInstance& e) {
  if (e.effect != Effect::kBandwidth) return "";
  sim::SensorModel probe;
  std::string ignored;
  if (!AddEffect(e, &probe, &ignored)) return "";
  const sim::BandLimitFamily* f = sim::FamilyOf(probe.band_limit);
  return f != nullptr ? std::string(f->name) : "";
}

bool HasSubtractiveDither(const EffectInstance& e) {
  const auto it = e.params.find("subtractive_dither");
  return e.effect == Effect::kRateQuantization && it != e.params.end() && it->second == 1.0;
}

std::string EffectVariant(const EffectInstance& e) {
  return HasSubtractiveDither(e) ? "subtractive dither" : FilterFamilyName(e);
}

std::string EffectLabel(const EffectInstance& e) {
  const std::string variant = EffectVariant(e);
  return std::string(EffectId(e.effect)) + (variant.empty() ? "" : " (" + variant + ")");
}

bool AddEffect(const EffectInstance& e, sim::SensorModel* model, std::string* why) {
  return SpecOf(e.effect).add(e, model, why);
}

bool IsOneOffEvent(Effect e) { return SpecOf(e).shift != nullptr; }

std::vector<Indistinguishable> AllanEquivalents(Effect e) { return SpecOf(e).allan_equivalents; }

bool HeldAtItsStart(const EffectInstance& e) {
  return e.effect == Effect::kRandomTelegraph && e.params.contains(std::string(kLevelSeparationParam));
}

bool EffectInstance::IsValid(double sample_rate_hz, std::string* why) const {
  for (const std::string& name : EffectParameterNames(effect)) {
    const auto it = params.find(name);
    if (it == params.end() || !std::isfinite(it->second)) {
      *why = std::string(EffectId(effect)) + ": parameter " + name + " missing or not finite";
      return false;
    }
  }
  sim::SensorModel probe;
  probe.sample_clock = SampleClock::FromRateHz(sample_rate_hz);
  return AddEffect(*this, &probe, why) && probe.IsValid(why);
}

}  // namespace allanlab::experiments
