#pragma once
// Starting values of a narrowband resonance from the record's Welch PSD: the line's peak gives
// f0, its half-power width 2 zeta f0 the damping, and the power above the local floor sigma^2.
#include <optional>
#include <span>
#include <string>

#include "experiments/diagnosis/effect.h"

namespace allanlab::experiments {

// How far a broad line's bump must stand above the wide floor, in standard errors of the smoothed
// Welch average (the largest of ~500 bins under the null reaches ~3.5).
inline constexpr double kBroadLineSe = 6.0;
// A broad bump wider than this damping (half-power width 2 zeta f0) is a hump of the floor, not
// a line (bumps of white noise's PSD before a band-limit's roll-off read 0.2-0.5).
inline constexpr double kBroadLineMaxDamping = 0.3;

// nullopt with *why when no line rises 1.5x above the PSD's local median over at least three
// adjacent bins and above the PSD 16 bins away on both sides (a Welch average of ~1e3 segments
// has a per-bin relative SE of ~4 %), nor a broad bump kBroadLineSe standard errors above the
// median over +-192 bins and above its flanks 64 or 128 bins out (resonance_estimate.cc).
std::optional<EffectInstance> EstimateResonance(std::span<const double> rate_rad_per_s, double tau0_s,
                                                std::string* why);

}  // namespace allanlab::experiments
