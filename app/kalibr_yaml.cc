#include "app/kalibr_yaml.h"

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

}  // namespace allanlab::app
