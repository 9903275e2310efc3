#pragma once
// The IMU noise file robotics users feed to Kalibr, VINS-Mono/Fusion and OpenVINS, gyroscope part.
// Those tools define continuous-time densities: gyroscope_noise_density [rad/s/sqrt(Hz)] is the
// ARW coefficient N in rad/sqrt(s), and gyroscope_random_walk [rad/s^2/sqrt(Hz)] is the RRW
// coefficient K in rad/s/sqrt(s). (imu_utils' gyr_n is a per-sample sigma, N sqrt(fs), not a
// density: that is not what is written here.)
#include <optional>
#include <string>
#include <vector>

#include "app/input/imu_columns.h"
#include "app/reports/provenance.h"

namespace allanlab::app {

// One key's value and what it is: an estimate (with its standard uncertainty, if known) or a
// 95 % upper bound (a term the data do not determine, or any value from a poor fit). A filter
// told 0 would take the bias as constant: an upper bound errs on the safe side.
struct KalibrValue {
  double value = 0.0;
  std::optional<double> sigma;
  bool upper_bound = false;
};

struct KalibrGyroNoise {
  KalibrValue noise_density;  // N in SI, rad/s/sqrt(Hz)
  KalibrValue random_walk;    // K in SI, rad/s^2/sqrt(Hz)
  double update_rate_hz = 0.0;
  // Non-empty: the fit did not describe the record; written as a warning comment on top.
  std::string warning;
};

// YAML text: provenance as comments, the warning if any, the two gyroscope keys (each saying
// whether it is an estimate or an upper bound), update_rate, and a comment that the accelerometer
// keys are not estimated by this file.
std::string KalibrImuYaml(const KalibrGyroNoise& noise, const Provenance& provenance);

// One axis of an IMU: a gyro's noise in the SI units above, an accelerometer's as
// accelerometer_noise_density [m/s^2/sqrt(Hz)] = VRW N in m/s/sqrt(s) and
// accelerometer_random_walk [m/s^3/sqrt(Hz)] = acceleration random walk K in m/s^2/sqrt(s).
struct KalibrAxisNoise {
  std::string column;
  ImuSensor sensor = ImuSensor::kGyro;
  KalibrGyroNoise noise;
};

// The whole IMU in one file: for each sensor present, the largest noise density and the largest
// random walk over its axes (one value per sensor is what these tools take; a filter told less
// noise than an axis has is overconfident, so the largest, where imu_utils averages the axes),
// each axis's values as comments, the warning of any axis, and update_rate. A sensor with no
// axis gets a comment saying its keys are not estimated here.
std::string KalibrImuYaml(const std::vector<KalibrAxisNoise>& axes, const Provenance& provenance);

}  // namespace allanlab::app
