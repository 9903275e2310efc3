#pragma once
// Pieces every noise term shares: where it enters the sensor's signal chain, parameter checks,
// and the Gaussian sample loop.
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

#include "sim/seeding.h"

namespace allanlab::sim {

// Where a term enters the sensor model (sim/sensor_model.h):
//  kWideband: generated at the band-limit's internal rate, then low-pass filtered and sampled
//             (white rate noise, harmonics: power above the output Nyquist frequency matters).
//  kHeld:     generated at the output rate, held over the internal steps, then filtered
//             (slow terms whose power above fs/2 is negligible: flicker, random walk, ...).
//  kDigital:  added after the band-limit, at the output rate (effects of the digitisation).
enum class SignalPath { kWideband, kHeld, kDigital };

// True when v is finite and >= 0; otherwise writes "<name> must be a finite number >= 0 ...".
bool CheckNonNegative(double v, std::string_view name, std::string* why);
// True when v is finite and > 0.
bool CheckPositive(double v, std::string_view name, std::string* why);

// out[i] += std_dev * z_i with z_i iid standard normal (Boost ziggurat), in index order.
void AddGaussian(Engine& engine, double std_dev, std::span<double> out);

}  // namespace allanlab::sim
