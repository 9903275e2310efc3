#pragma once
// Sensor models written by people, in YAML with units on every value, and the shipped presets.
//
//   name: mg25_mems
//   description: "..."
//   sample_rate: 200 Hz            # default output rate (the CLI's --rate overrides it)
//   bias: 0.2 deg/s                # optional constant turn-on bias
//   terms:                         # any number, in any order; same type may repeat
//     - {type: quantization, Q: 0.5 urad}
//     - {type: arw, N: 0.0267 deg/sqrt(h)}
//     - {type: bias_instability, B: 0.181 deg/h}
//     - {type: bias_instability_gm_sum, B: .., min_correlation_time: .., max_correlation_time: ..,
//        per_decade: 1}
//     - {type: rrw, K: 0.3 deg/h/sqrt(h)}
//     - {type: ramp, R: 1 deg/h^2}
//     - {type: harmonic, amplitude: 2 deg/h, frequency: 7.3 Hz, phase: 0.3 rad}   # phase optional
//     - {type: gauss_markov, sigma: 1 deg/h, correlation_time: 100 s}
//     - {type: random_telegraph, amplitude: 1 deg/h, mean_dwell: 30 s}
//     - {type: exponential_drift, amplitude: 5 deg/h, time_constant: 600 s}
//     - {type: bias_step, size: 1 deg/h, time: 1800 s}
//     - {type: outliers, rate: 0.01 Hz, size: 2 deg/s}
//   band_limit: {type: first_order|butterworth2|none, cutoff: 100 Hz, oversampling: 8,
//                sampling: point|average}
//   output: {angle_lsb: 1 urad, rate_lsb: 0.05 deg/s,     # both optional
//            rate_dither: none|subtractive}              # optional, default none
//
// Unknown keys, missing units, wrong units and invalid values are rejected with the key's path
// (e.g. "terms[2].N: ...").
#include <string>
#include <string_view>
#include <vector>

#include "sim/sensor_model.h"

namespace allanlab::sim {

// Parses YAML text into *model and validates it (SensorModel::IsValid). `origin` names the
// source in messages (a file path or "preset mg25_mems").
bool LoadSensorModelYaml(std::string_view yaml_text, std::string_view origin, SensorModel* model,
                         std::string* why);
// Reads and parses a file; a missing or unreadable file is an error with the path in it.
bool LoadSensorModelFile(const std::string& path, SensorModel* model, std::string* why);

// Names of the shipped presets (sim/presets/*.yaml, embedded in the binary), sorted.
std::vector<std::string> PresetNames();
// Loads a shipped preset; an unknown name is an error listing the known ones.
bool LoadPreset(std::string_view name, SensorModel* model, std::string* why);

}  // namespace allanlab::sim
