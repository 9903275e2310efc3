#include "independent/generate.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "independent/low_pass_chain.h"
#include "independent/random_stream.h"
#include "independent/signal_terms.h"

namespace allanlab::independent {
namespace {

// One random stream per component: (seed, stream, component id).
enum Component : std::uint64_t {
  kWhite = 1, kFlicker, kRandomWalk, kGaussMarkov, kTelegraph, kSinusoid, kResonance, kSpikes, kQuantizer
};

void FillWhite(const Noise& z, double variance, RandomStream& rng, std::span<double> out) {
  const double sd = std::sqrt(variance);
  switch (z.white_law) {
    case WhiteLaw::kGaussian:
      for (double& y : out) y += sd * rng.Normal();
      break;
    case WhiteLaw::kStudentT: {
      const double unit = std::sqrt((z.student_t_dof - 2.0) / z.student_t_dof);
      for (double& y : out) y += sd * unit * rng.StudentT(z.student_t_dof);
      break;
    }
    case WhiteLaw::kLaplace:
      for (double& y : out) y += sd * std::sqrt(0.5) * rng.Laplace();
      break;
  }
}

void Validate(const Recipe& r, std::int64_t n) {
  std::string why;
  if (!r.IsValid(n, &why)) throw std::invalid_argument("independent recipe: " + why);
}

// Steps 3-5 of the chain (recipe.h).
void AddSlowTermsAndEffects(const Recipe& r, std::uint64_t seed, std::uint64_t stream, std::span<double> y) {
  const double h = r.sample_period_s();
  auto rng = [&](Component c) { return RandomStream(seed, stream, c); };
  for (double& v : y) v += r.noise.bias_rad_per_s;
  if (r.noise.flicker_floor_rad_per_s > 0.0) {
    RandomStream g = rng(kFlicker);
    AddFlicker(r.noise.flicker_floor_rad_per_s, g, y);
  }
  if (r.noise.rrw_rad_per_s_per_sqrt_s > 0.0) {
    RandomStream g = rng(kRandomWalk);
    AddRandomWalk(r.noise.rrw_rad_per_s_per_sqrt_s, h, g, y);
  }
  AddRamp(r.noise.ramp_rad_per_s2, h, y);
  if (r.gauss_markov) {
    RandomStream g = rng(kGaussMarkov);
    AddGaussMarkov(*r.gauss_markov, h, g, y);
  }
  if (r.telegraph) {
    RandomStream g = rng(kTelegraph);
    AddTelegraph(*r.telegraph, h, g, y);
  }
  if (r.sinusoid) {
    RandomStream g = rng(kSinusoid);
    AddSinusoid(*r.sinusoid, h, g, y);
  }
  if (r.resonance) {
    RandomStream g = rng(kResonance);
    AddResonance(*r.resonance, h, g, y);
  }
  if (r.bias_step) AddBiasStep(*r.bias_step, h, y);
  if (r.warmup_drift) AddWarmupDrift(*r.warmup_drift, h, y);
  if (r.angle_quantizer) {
    RandomStream g = rng(kQuantizer);
    QuantizeAngle(*r.angle_quantizer, h, g, y);
  }
  if (r.rate_quantizer) {
    RandomStream g = rng(kQuantizer);
    QuantizeRate(*r.rate_quantizer, g, y);
  }
  if (r.spikes) {
    RandomStream g = rng(kSpikes);
    AddSpikes(*r.spikes, h, g, y);
  }
}

}  // namespace

std::vector<double> Generate(const Recipe& r, std::int64_t n, std::uint64_t seed, std::uint64_t stream) {
  Validate(r, n);
  std::vector<double> y(static_cast<std::size_t>(n), 0.0);
  const int L = r.internal_oversampling();
  const double fs_int = r.rate_hz * L;
  const double white_variance = r.noise.arw_rad_per_sqrt_s * r.noise.arw_rad_per_sqrt_s * fs_int;  // N^2 / tau_int
  if (r.low_pass.design == LowPassDesign::kNone) {
    if (white_variance > 0.0) {
      RandomStream g(seed, stream, kWhite);
      FillWhite(r.noise, white_variance, g, y);
    }
  } else {
    const std::int64_t warm = WarmupSamples(r.low_pass, fs_int);
    std::vector<double> internal(static_cast<std::size_t>(warm + n * L), 0.0);
    if (white_variance > 0.0) {
      RandomStream g(seed, stream, kWhite);
      FillWhite(r.noise, white_variance, g, internal);
    }
    FilterAndDecimate(r.low_pass, fs_int, internal, y);
  }
  AddSlowTermsAndEffects(r, seed, stream, y);
  return y;
}

void Inject(const Recipe& r, std::uint64_t seed, std::uint64_t stream, std::span<double> y) {
  Validate(r, static_cast<std::int64_t>(y.size()));
  const double white_variance = r.noise.arw_rad_per_sqrt_s * r.noise.arw_rad_per_sqrt_s * r.rate_hz;
  if (white_variance > 0.0) {
    RandomStream g(seed, stream, kWhite);
    FillWhite(r.noise, white_variance, g, y);
  }
  if (r.low_pass.design != LowPassDesign::kNone) {
    LowPass lp = r.low_pass;
    lp.oversampling = 1;
    if (lp.design != LowPassDesign::kCic && !(lp.cutoff_hz < 0.5 * r.rate_hz)) {
      throw std::invalid_argument("independent recipe: an injected low-pass needs a cutoff below the recording's Nyquist frequency");
    }
    const std::int64_t warm = WarmupSamples(lp, r.rate_hz);
    // The recording's first samples, reflected, settle the filter.
    std::vector<double> internal(static_cast<std::size_t>(warm) + y.size());
    for (std::int64_t i = 0; i < warm; ++i) {
      internal[static_cast<std::size_t>(i)] = y[static_cast<std::size_t>((warm - i) % static_cast<std::int64_t>(y.size()))];
    }
    std::copy(y.begin(), y.end(), internal.begin() + warm);
    FilterAndDecimate(lp, r.rate_hz, internal, y);
  }
  AddSlowTermsAndEffects(r, seed, stream, y);
}

}  // namespace allanlab::independent
