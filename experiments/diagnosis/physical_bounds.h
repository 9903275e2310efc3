#pragma once
// The one place that states which fitted effects are physically impossible for a record sampled
// at fs over T seconds. A candidate whose fit lands outside these is refused (listed as skipped
// with the reason), never reported, however much it lowers chi2: such a fit is the optimiser
// using a parameter as a free shape, not a property of the sensor.
//   bandwidth           cutoff below the output Nyquist frequency fs/2 (above it the filter
//                       leaves no trace a record can locate)
//   gauss_markov        correlation time Tc >= the sample period 1/fs
//   random_telegraph    correlation time (mean dwell / 2) >= 1/fs
//   harmonic            frequency below fs/2
//   resonance           frequency below fs/2, damping < 1 and a decay time 1/(zeta w0) >= 1/fs
//                       (a line narrower than the band it sits in), and a line width
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

// False with *why naming the effect, the parameter and the bound it breaks.
bool PhysicallyPossible(const EffectInstance& effect, SampleClock sample_clock, double record_length_s,
                        std::string* why);
bool PhysicallyPossible(std::span<const EffectInstance> effects, SampleClock sample_clock,
                        double record_length_s, std::string* why);

}  // namespace allanlab::experiments
