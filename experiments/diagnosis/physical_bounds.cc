#include "experiments/diagnosis/physical_bounds.h"

#include <cmath>
#include <numbers>
#include <sstream>

#include "estimators/fit/parametric_term.h"
#include "sim/band_limit.h"
#include "sim/sensor_model.h"

namespace allanlab::experiments {

bool PhysicallyPossible(const EffectInstance& e, SampleClock sample_clock, double record_length_s, std::string* why) {
  auto p = [&](const char* name) {
    const auto it = e.params.find(name);
    return it == e.params.end() ? std::nan("") : it->second;
  };
  const double tau0 = sample_clock.period_s(), nyquist = 0.5 * sample_clock.rate_hz();
  std::ostringstream os;
  os << EffectLabel(e) << ": ";
  bool ok = true;
  switch (e.effect) {
    case Effect::kBandwidth: {
      // The chain the filter runs in: L x fs internally, before the output's decimation.
      sim::SensorModel probe;
      probe.sample_clock = sample_clock;
      std::string ignored;
      const int oversampling = AddEffect(e, &probe, &ignored) ? probe.band_limit.oversampling : 1;
      const double internal_rate_hz = oversampling * sample_clock.rate_hz();
      const double edge_hz =
          kBoundShare * estimators::BandLimitMaxCutoffHz(probe.band_limit.kind, oversampling, sample_clock.period_s());
      // A filter running at the output rate has its highest cutoff (0.45 fs) where it still bends
      // the shortest taus: a cutoff there is a real digital filter's (sim/'s benchmark draws
      // 45 Hz Butterworths at 100 Hz, fitted at 44.6-45.0 Hz with chi2 29 on ~50 taus), not one
      // the curve cannot see. Only a chain running faster than the output can hide its filter.
      if (oversampling > 1 && !(p("cutoff_hz") < edge_hz)) {
        os << "cutoff " << p("cutoff_hz") << " Hz is at the highest cutoff its filter running at " << internal_rate_hz
           << " Hz can take (" << edge_hz << " Hz): the fit ran to its edge, the cutoff is not determined";
        ok = false;
      }
      break;
    }
    case Effect::kGaussMarkov:
    case Effect::kRandomTelegraph: {
      const bool telegraph = e.effect == Effect::kRandomTelegraph;
      const double tc = telegraph ? 0.5 * p("mean_dwell_s") : p("correlation_time_s");
      const char* what = telegraph ? "correlation time (mean dwell / 2) " : "correlation time ";
      if (!(tc >= tau0)) {
        os << what << tc << " s is below the sample period " << tau0 << " s";
        ok = false;
      } else if (!(tc <= 0.5 * record_length_s)) {
        os << what << tc << " s is longer than half the record (" << 0.5 * record_length_s
           << " s): over the record such a process is a random walk of the rate, which K describes, and its "
              "correlation time is not determined";
        ok = false;
      }
      break;
    }
    case Effect::kHarmonic:
      if (!(p("frequency_hz") < nyquist)) {
        os << "frequency " << p("frequency_hz") << " Hz is not below the Nyquist frequency " << nyquist << " Hz";
        ok = false;
      }
      break;
    case Effect::kResonance: {
      const double decay_s = 1.0 / (p("damping") * 2.0 * std::numbers::pi * p("frequency_hz"));
      if (!(p("frequency_hz") < nyquist)) {
        os << "frequency " << p("frequency_hz") << " Hz is not below the Nyquist frequency " << nyquist << " Hz";
        ok = false;
      } else if (!(p("damping") < 1.0) || !(decay_s >= tau0)) {
        os << "decay time " << decay_s << " s (damping " << p("damping") << ") is below the sample period " << tau0
           << " s: not a line";
        ok = false;
      } else if (!(p("damping") < std::numbers::sqrt2 / 2.0)) {
        // A damped oscillator driven by white noise has a peak in its spectrum only below
        // 1/sqrt(2); above it is a correlated wander whose Allan bump a Gauss-Markov process
        // (one parameter fewer) draws as well (benchmark: a 1.4 s Gauss-Markov fitted as a
        // 0.23 Hz "resonance" of damping 0.95).
        os << "damping " << p("damping") << " leaves no peak in the spectrum (a line needs damping below 0.707): "
           << "a correlated wander, not a line";
        ok = false;
      } else if (!(p("damping") > estimators::kResonanceMinDamping / kBoundShare)) {
        // The fit ran to its floor: the record's line is narrower than any damping it may take.
        os << "damping " << p("damping") << " is at the fit's floor " << estimators::kResonanceMinDamping
           << ": a line of constant amplitude over the record, a sinusoid, the harmonic";
        ok = false;
      } else if (!(2.0 * p("damping") * p("frequency_hz") * record_length_s >= 1.0)) {
        // A line narrower than the record's frequency resolution keeps its amplitude over the
        // record: a sinusoid (the harmonic candidate), whose amplitude the Monte Carlo would
        // instead draw anew per trial, widening the envelope the record is judged against.
        os << "line width " << 2.0 * p("damping") * p("frequency_hz") << " Hz (damping " << p("damping")
           << ") is narrower than the record's resolution " << 1.0 / record_length_s
           << " Hz: over this record a sinusoid, the harmonic";
        ok = false;
      }
      break;
    }
    case Effect::kExponentialDrift:
      if (!(p("time_constant_s") >= tau0)) {
        os << "time constant " << p("time_constant_s") << " s is below the sample period " << tau0 << " s";
        ok = false;
      }
      break;
    case Effect::kBiasStep:
      if (!(p("time_s") > 0.0 && p("time_s") < record_length_s)) {
        os << "step time " << p("time_s") << " s is outside the record (0, " << record_length_s << " s)";
        ok = false;
      }
      break;
    case Effect::kAngleQuantization:
    case Effect::kRateQuantization:
    case Effect::kOutliers:
      break;
  }
  if (!ok && why) *why = "refused as physically impossible: " + os.str();
  return ok;
}

bool PhysicallyPossible(std::span<const EffectInstance> effects, SampleClock sample_clock, double record_length_s,
                        std::string* why) {
  for (const EffectInstance& e : effects) {
    if (!PhysicallyPossible(e, sample_clock, record_length_s, why)) return false;
  }
  return true;
}

}  // namespace allanlab::experiments
