#pragma once
// Starting values of a narrowband resonance from the record's Welch PSD: the line's peak gives
// f0, its half-power width 2 zeta f0 the damping, and the power above the local floor sigma^2.
#include <optional>
#include <span>
#include <string>

#include "experiments/diagnosis/effect.h"

namespace allanlab::experiments {

// nullopt with *why when no line rises 1.5x above the PSD's local median over at least three
// adjacent bins (a Welch average of ~1e3 segments has a per-bin relative SE of ~4 %).
std::optional<EffectInstance> EstimateResonance(std::span<const double> rate_rad_per_s, double tau0_s,
                                                std::string* why);

}  // namespace allanlab::experiments
