#include "app/kalibr_yaml.h"

namespace allanlab::app {

std::string KalibrImuYaml(const KalibrGyroNoise& noise, const Provenance& provenance) {
  std::string out = ProvenanceCommentLines(provenance);
  out += "# Gyroscope noise for Kalibr / VINS / OpenVINS (continuous-time densities).\n";
  out += "# Accelerometer keys are not estimated here: fit the accelerometer axes separately.\n";
  auto sigma = [](const std::optional<double>& s) {
    return s ? "  # +- " + ShortestDecimal(*s) + " (1 sigma)" : std::string();
  };
  out += "gyroscope_noise_density: " + ShortestDecimal(noise.noise_density_rad_per_s_per_sqrt_hz) +
         sigma(noise.noise_density_sigma) + "  # rad/s/sqrt(Hz) = ARW N in rad/sqrt(s)\n";
  out += "gyroscope_random_walk: " + ShortestDecimal(noise.random_walk_rad_per_s2_per_sqrt_hz) +
         sigma(noise.random_walk_sigma) + "  # rad/s^2/sqrt(Hz) = RRW K in rad/s/sqrt(s)\n";
  out += "update_rate: " + ShortestDecimal(noise.update_rate_hz) + "  # Hz\n";
  return out;
}

}  // namespace allanlab::app
