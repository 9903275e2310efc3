#include "experiments/diagnosis/effect.h"

#include <cmath>

namespace allanlab::experiments {
namespace {

struct EffectInfo {
  Effect effect;
  std::string_view id;
  std::vector<std::string> params;
};

const std::vector<EffectInfo>& Table() {
  static const std::vector<EffectInfo> table = {
      {Effect::kBandwidth, "bandwidth", {"cutoff_hz", "order"}},
      {Effect::kGaussMarkov, "gauss_markov", {"sigma_rad_per_s", "correlation_time_s"}},
      {Effect::kRandomTelegraph, "random_telegraph", {"amplitude_rad_per_s", "mean_dwell_s"}},
      {Effect::kHarmonic, "harmonic", {"amplitude_rad_per_s", "frequency_hz"}},
      {Effect::kAngleQuantization, "angle_quantization", {"lsb_rad"}},
      {Effect::kRateQuantization, "rate_quantization", {"lsb_rad_per_s"}},
      {Effect::kExponentialDrift, "exponential_drift", {"amplitude_rad_per_s", "time_constant_s"}},
      {Effect::kBiasStep, "bias_step", {"size_rad_per_s", "time_s"}},
      {Effect::kOutliers, "outliers", {"rate_hz", "size_rad_per_s"}},
  };
  return table;
}

const EffectInfo& Info(Effect e) {
  for (const EffectInfo& info : Table()) {
    if (info.effect == e) return info;
  }
  return Table().front();  // unreachable: the table covers the enum
}

}  // namespace

std::string_view EffectId(Effect e) { return Info(e).id; }

bool ParseEffect(std::string_view id, Effect* e) {
  for (const EffectInfo& info : Table()) {
    if (info.id == id) {
      *e = info.effect;
      return true;
    }
  }
  return false;
}

std::vector<std::string> EffectParameterNames(Effect e) { return Info(e).params; }

bool EffectInstance::IsValid(double sample_rate_hz, std::string* why) const {
  for (const std::string& name : EffectParameterNames(effect)) {
    const auto it = params.find(name);
    if (it == params.end() || !std::isfinite(it->second)) {
      *why = std::string(EffectId(effect)) + ": parameter " + name + " missing or not finite";
      return false;
    }
  }
  sim::SensorModel probe;
  probe.sample_rate_hz = sample_rate_hz;
  return AddEffect(*this, &probe, why) && probe.IsValid(why);
}

bool AddEffect(const EffectInstance& e, sim::SensorModel* model, std::string* why) {
  auto p = [&](const char* name) {
    const auto it = e.params.find(name);
    return it == e.params.end() ? std::nan("") : it->second;
  };
  switch (e.effect) {
    case Effect::kBandwidth: {
      if (model->band_limit.enabled()) {
        *why = "the model already has a band-limit";
        return false;
      }
      const double order = p("order");
      if (order != 1.0 && order != 2.0) {
        *why = "bandwidth: order must be 1 or 2";
        return false;
      }
      model->band_limit.kind =
          order == 1.0 ? sim::LowPassKind::kFirstOrder : sim::LowPassKind::kButterworth2;
      model->band_limit.cutoff_hz = p("cutoff_hz");
      // Point sampling of the filtered internal signal: the analog chain of sim/band_limit.h.
      model->band_limit.sampling = sim::OutputSampling::kPoint;
      return model->band_limit.IsValid(model->sample_rate_hz, why);
    }
    case Effect::kGaussMarkov: {
      sim::GaussMarkov t;
      t.sigma_rad_per_s = p("sigma_rad_per_s");
      t.correlation_time_s = p("correlation_time_s");
      if (!t.IsValid(why)) return false;
      model->terms.push_back(t);
      return true;
    }
    case Effect::kRandomTelegraph: {
      sim::RandomTelegraph t;
      t.amplitude_rad_per_s = p("amplitude_rad_per_s");
      t.mean_dwell_s = p("mean_dwell_s");
      if (!t.IsValid(why)) return false;
      model->terms.push_back(t);
      return true;
    }
    case Effect::kHarmonic: {
      sim::Harmonic t;
      t.amplitude_rad_per_s = p("amplitude_rad_per_s");
      t.frequency_hz = p("frequency_hz");
      if (!t.IsValid(why)) return false;
      model->terms.push_back(t);
      return true;
    }
    case Effect::kAngleQuantization: {
      sim::AngleQuantizer q;
      q.lsb_rad = p("lsb_rad");
      if (!q.IsValid(why)) return false;
      model->angle_quantizer = q;
      return true;
    }
    case Effect::kRateQuantization: {
      sim::RateQuantizer q;
      q.lsb_rad_per_s = p("lsb_rad_per_s");
      if (!q.IsValid(why)) return false;
      model->rate_quantizer = q;
      return true;
    }
    case Effect::kExponentialDrift: {
      sim::ExponentialDrift t;
      t.amplitude_rad_per_s = p("amplitude_rad_per_s");
      t.time_constant_s = p("time_constant_s");
      if (!t.IsValid(why)) return false;
      model->terms.push_back(t);
      return true;
    }
    case Effect::kBiasStep: {
      sim::BiasStep t;
      t.size_rad_per_s = p("size_rad_per_s");
      t.time_s = p("time_s");
      if (!t.IsValid(why)) return false;
      model->terms.push_back(t);
      return true;
    }
    case Effect::kOutliers: {
      sim::Outliers t;
      t.rate_hz = p("rate_hz");
      t.size_rad_per_s = p("size_rad_per_s");
      if (!t.IsValid(why)) return false;
      model->terms.push_back(t);
      return true;
    }
  }
  *why = "unknown effect";
  return false;
}

std::vector<Indistinguishable> AllanEquivalents(Effect e) {
  // A telegraph signal of amplitude a and mean dwell T has the autocovariance a^2 e^{-2|t|/T}
  // of a Gauss-Markov process with sigma = a, Tc = T/2 (sim/random_telegraph.h): every
  // second-moment view (Allan, Hadamard, PSD) is the same; the increments' kurtosis is not.
  if (e == Effect::kGaussMarkov) return {{Effect::kRandomTelegraph, "kurtosis"}};
  if (e == Effect::kRandomTelegraph) return {{Effect::kGaussMarkov, "kurtosis"}};
  return {};
}

}  // namespace allanlab::experiments
