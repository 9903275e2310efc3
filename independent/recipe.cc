#include "independent/recipe.h"

#include <cmath>
#include <sstream>

namespace allanlab::independent {
namespace {

bool Check(bool ok, const std::string& what, std::string* why) {
  if (!ok) *why = what;
  return ok;
}
bool NonNegative(double v) { return std::isfinite(v) && v >= 0.0; }
bool Positive(double v) { return std::isfinite(v) && v > 0.0; }

}  // namespace

double FlickerFloorFromB(double b_rad_per_s) { return std::sqrt(2.0 * std::log(2.0) / M_PI) * b_rad_per_s; }

bool Recipe::IsValid(std::int64_t n, std::string* why) const {
  if (!Check(Positive(rate_hz), "rate_hz must be positive and finite", why)) return false;
  if (!Check(n >= 16, "a record needs at least 16 samples", why)) return false;
  const double fs = rate_hz, duration = static_cast<double>(n) / fs;
  const Noise& z = noise;
  if (!Check(NonNegative(z.arw_rad_per_sqrt_s) && NonNegative(z.flicker_floor_rad_per_s) &&
                 NonNegative(z.rrw_rad_per_s_per_sqrt_s) && std::isfinite(z.ramp_rad_per_s2) &&
                 std::isfinite(z.bias_rad_per_s),
             "noise coefficients must be finite (N, flicker floor and K non-negative)", why))
    return false;
  if (!Check(z.white_law != WhiteLaw::kStudentT || (std::isfinite(z.student_t_dof) && z.student_t_dof > 4.0),
             "student_t_dof must be > 4 (finite kurtosis)", why))
    return false;
  const LowPass& lp = low_pass;
  if (lp.design != LowPassDesign::kNone) {
    if (!Check(lp.oversampling >= 1 && lp.oversampling <= 256, "low_pass.oversampling must be in [1, 256]", why))
      return false;
    if (lp.design == LowPassDesign::kCic) {
      if (!Check(lp.cic_stages >= 1 && lp.cic_stages <= 8, "low_pass.cic_stages must be in [1, 8]", why)) return false;
    } else if (!Check(Positive(lp.cutoff_hz) && lp.cutoff_hz < 0.5 * fs * lp.oversampling,
                      "low_pass.cutoff_hz must be positive and below the internal Nyquist frequency", why)) {
      return false;
    }
  }
  if (gauss_markov && !Check(NonNegative(gauss_markov->sigma_rad_per_s) && Positive(gauss_markov->correlation_time_s),
                             "gauss_markov: sigma >= 0 and correlation_time_s > 0 required", why))
    return false;
  if (telegraph && !Check(NonNegative(telegraph->amplitude_rad_per_s) && Positive(telegraph->mean_dwell_s),
                          "telegraph: amplitude >= 0 and mean_dwell_s > 0 required", why))
    return false;
  if (sinusoid && !Check(NonNegative(sinusoid->amplitude_rad_per_s) && Positive(sinusoid->frequency_hz) &&
                             (!sinusoid->phase_rad || std::isfinite(*sinusoid->phase_rad)),
                         "sinusoid: amplitude >= 0, frequency_hz > 0 and a finite phase required", why))
    return false;
  if (resonance && !Check(NonNegative(resonance->sigma_rad_per_s) && Positive(resonance->frequency_hz) &&
                              resonance->frequency_hz < 0.5 * fs && resonance->damping_ratio > 0.0 &&
                              resonance->damping_ratio < 1.0,
                          "resonance: sigma >= 0, 0 < frequency_hz < fs/2 and 0 < damping_ratio < 1 required", why))
    return false;
  if (bias_step && !Check(std::isfinite(bias_step->size_rad_per_s) && NonNegative(bias_step->time_s) &&
                              bias_step->time_s <= duration,
                          "bias_step: finite size and a time inside the record required", why))
    return false;
  if (warmup_drift && !Check(std::isfinite(warmup_drift->amplitude_rad_per_s) && Positive(warmup_drift->time_constant_s),
                             "warmup_drift: finite amplitude and time_constant_s > 0 required", why))
    return false;
  if (spikes && !Check(NonNegative(spikes->rate_hz) && spikes->rate_hz <= fs && NonNegative(spikes->scale_rad_per_s) &&
                           std::isfinite(spikes->tail_index) && spikes->tail_index > 2.0,
                       "spikes: 0 <= rate_hz <= fs, scale >= 0 and tail_index > 2 required", why))
    return false;
  if (angle_quantizer && !Check(Positive(angle_quantizer->lsb_rad), "angle_quantizer.lsb_rad must be positive", why))
    return false;
  if (rate_quantizer && !Check(Positive(rate_quantizer->lsb_rad_per_s), "rate_quantizer.lsb_rad_per_s must be positive", why))
    return false;
  if (!Check(!(angle_quantizer && rate_quantizer), "one output quantizer at most (angle or rate)", why)) return false;
  return true;
}

}  // namespace allanlab::independent
