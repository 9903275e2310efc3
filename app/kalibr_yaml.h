#pragma once
// The IMU noise file robotics users feed to Kalibr, VINS-Mono/Fusion and OpenVINS, gyroscope part.
// Those tools define continuous-time densities: gyroscope_noise_density [rad/s/sqrt(Hz)] is the
// ARW coefficient N in rad/sqrt(s), and gyroscope_random_walk [rad/s^2/sqrt(Hz)] is the RRW
// coefficient K in rad/s/sqrt(s). (imu_utils' gyr_n is a per-sample sigma, N sqrt(fs), not a
// density: that is not what is written here.)
#include <optional>
#include <string>

#include "app/provenance.h"

namespace allanlab::app {

struct KalibrGyroNoise {
  double noise_density_rad_per_s_per_sqrt_hz = 0.0;  // N in SI
  std::optional<double> noise_density_sigma;        // its standard uncertainty, if known
  double random_walk_rad_per_s2_per_sqrt_hz = 0.0;   // K in SI (0 when not supported by the data)
  std::optional<double> random_walk_sigma;
  double update_rate_hz = 0.0;
};

// YAML text: provenance as comments, the two gyroscope keys, update_rate, and a comment that the
// accelerometer keys are not estimated by this file.
std::string KalibrImuYaml(const KalibrGyroNoise& noise, const Provenance& provenance);

}  // namespace allanlab::app
