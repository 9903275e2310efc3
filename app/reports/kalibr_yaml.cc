#include "app/reports/kalibr_yaml.h"
#include "common/number_text.h"

namespace allanlab::app {
namespace {

std::string Comment(const KalibrValue& v) {
  if (v.upper_bound) return "  # 95 % upper bound (conservative)";
  return v.sigma ? "  # +- " + ShortestDecimal(*v.sigma) + " (1 sigma)" : std::string();
}

}  // namespace

std::string KalibrImuYaml(const KalibrGyroNoise& noise, const Provenance& provenance) {
  std::string out = ProvenanceCommentLines(provenance);
  if (!noise.warning.empty()) out += "# WARNING: " + noise.warning + "\n";
  out += "# Gyroscope noise for Kalibr / VINS / OpenVINS (continuous-time densities).\n";
  out += "# Accelerometer keys are not estimated here: fit the accelerometer axes separately.\n";
  out += "gyroscope_noise_density: " + ShortestDecimal(noise.noise_density.value) +
         Comment(noise.noise_density) + "  # rad/s/sqrt(Hz) = ARW N in rad/sqrt(s)\n";
  out += "gyroscope_random_walk: " + ShortestDecimal(noise.random_walk.value) +
         Comment(noise.random_walk) + "  # rad/s^2/sqrt(Hz) = RRW K in rad/s/sqrt(s)\n";
  out += "update_rate: " + ShortestDecimal(noise.update_rate_hz) + "  # Hz\n";
  return out;
}

namespace {

// The key with the largest value over `axes` of one sensor (`pick` chooses the density or the
// random walk), as "key: value  # ...", then a comment line per axis.
std::string LargestOverAxes(const std::vector<const KalibrAxisNoise*>& axes, const std::string& key,
                            const KalibrValue KalibrGyroNoise::*pick, const std::string& unit_note) {
  const KalibrAxisNoise* largest = axes.front();
  for (const KalibrAxisNoise* a : axes) {
    if ((a->noise.*pick).value > (largest->noise.*pick).value) largest = a;
  }
  std::string out = key + ": " + ShortestDecimal((largest->noise.*pick).value) + Comment(largest->noise.*pick) +
                    "  # " + unit_note + "; the largest of the axes (" + largest->column + ")\n";
  for (const KalibrAxisNoise* a : axes) {
    out += "#   " + a->column + ": " + ShortestDecimal((a->noise.*pick).value) + Comment(a->noise.*pick) + "\n";
  }
  return out;
}

}  // namespace

std::string KalibrImuYaml(const std::vector<KalibrAxisNoise>& axes, const Provenance& provenance) {
  std::string out = ProvenanceCommentLines(provenance);
  std::vector<const KalibrAxisNoise*> gyro, accel;
  double rate_hz = 0.0;
  for (const KalibrAxisNoise& a : axes) {
    (a.sensor == ImuSensor::kGyro ? gyro : accel).push_back(&a);
    if (!a.noise.warning.empty()) out += "# WARNING: " + a.column + ": " + a.noise.warning + "\n";
    rate_hz = a.noise.update_rate_hz;
  }
  out += "# IMU noise for Kalibr / VINS / OpenVINS (continuous-time densities), one value per sensor:\n";
  out += "# the largest over its axes (each axis below its key; imu_utils would average them).\n";
  if (gyro.empty()) {
    out += "# Gyroscope keys are not estimated here: no gyro column was fitted.\n";
  } else {
    out += LargestOverAxes(gyro, "gyroscope_noise_density", &KalibrGyroNoise::noise_density,
                           "rad/s/sqrt(Hz) = ARW N in rad/sqrt(s)");
    out += LargestOverAxes(gyro, "gyroscope_random_walk", &KalibrGyroNoise::random_walk,
                           "rad/s^2/sqrt(Hz) = RRW K in rad/s/sqrt(s)");
  }
  if (accel.empty()) {
    out += "# Accelerometer keys are not estimated here: no accelerometer column was fitted.\n";
  } else {
    out += LargestOverAxes(accel, "accelerometer_noise_density", &KalibrGyroNoise::noise_density,
                           "m/s^2/sqrt(Hz) = VRW N in m/s/sqrt(s)");
    out += LargestOverAxes(accel, "accelerometer_random_walk", &KalibrGyroNoise::random_walk,
                           "m/s^3/sqrt(Hz) = acceleration random walk K in m/s^2/sqrt(s)");
  }
  out += "update_rate: " + ShortestDecimal(rate_hz) + "  # Hz\n";
  return out;
}

}  // namespace allanlab::app
