#pragma once
// The one place that states which fitted effects are physically impossible for a record sampled
// at fs over T seconds. A candidate whose fit lands outside these is refused (listed as skipped
// with the reason), never reported, however much it lowers chi2: such a fit is the optimiser
// using a parameter as a free shape, not a property of the sensor.
//   bandwidth           cutoff below 98 % of the highest its filter can take, 0.45 L fs (0.3 L fs
//                       for a box), L fs the rate the filter runs at before the output's
//                       decimation (the fit's own bound, estimators/fit/parametric_term.h): a fit
//                       at that edge has not determined the cutoff. Above the output Nyquist
//                       frequency fs/2 it is still a real sensor's filter (an anti-alias filter
//                       at several times fs, then averaged to the output: the independent
//                       benchmark's 86.8 Hz filter at fs = 100 Hz was fitted at 85.4 Hz). A
//                       filter at the output rate (L = 1) is kept up to its edge 0.45 fs, where
//                       it still bends the shortest taus (a 45 Hz digital Butterworth at 100 Hz)
//   gauss_markov        correlation time Tc >= the sample period 1/fs, and <= T/2: a longer one
//                       is, over the record, a random walk of the rate that K describes (its Allan
//                       bump peaks at 1.9 Tc, beyond the curve's last tau T/2), not determined
//                       (the independent benchmark's -35 deg/h bias step, seed 4 #67, was named a
//                       Gauss-Markov of Tc 5902 s in a 1931 s record, its held-out chi2 155
//                       against the step's 48)
//   random_telegraph    correlation time (mean dwell / 2) >= 1/fs and <= T/2, as Gauss-Markov
//   harmonic            frequency below fs/2
//   resonance           frequency below fs/2, damping < 1 and a decay time 1/(zeta w0) >= 1/fs
//                       (a line narrower than the band it sits in), damping below 1/sqrt(2)
//                       (above it the spectrum has no peak: a correlated wander, the
//                       Gauss-Markov's), damping above the fit's
//                       floor (at it, the record's line is a sinusoid: two independent
//                       benchmark sinusoids were named resonances at damping 0.001), and a line width
//                       2 zeta f0 >= 1/T: a narrower line keeps its amplitude over the record, a
//                       sinusoid that the harmonic describes (a 0.5 Hz sinusoid in 360 s was
//                       fitted as a resonance at the damping's lower bound, 0.001)
//   exponential_drift   time constant >= 1/fs
//   bias_step           time inside the record (0, T)
#include <span>
#include <string>

#include "common/sample_clock.h"
#include "experiments/diagnosis/effect.h"

namespace allanlab::experiments {

// How close to one of its fit's bounds a parameter counts as at that bound (not determined): within
// 2 % of a band-limit's highest cutoff, below 1.02x the resonance's lowest damping.
inline constexpr double kBoundShare = 0.98;

// False with *why naming the effect, the parameter and the bound it breaks.
bool PhysicallyPossible(const EffectInstance& effect, SampleClock sample_clock, double record_length_s,
                        std::string* why);
bool PhysicallyPossible(std::span<const EffectInstance> effects, SampleClock sample_clock,
                        double record_length_s, std::string* why);

}  // namespace allanlab::experiments
