// Kalibr's gyroscope keys are the continuous-time densities: N in rad/sqrt(s) and K in
// rad/s/sqrt(s) (docs/theory.md §1.5), written with their units.
#include <string>

#include <gtest/gtest.h>

#include "app/reports/kalibr_yaml.h"
#include "common/number_text.h"
#include "sim/units.h"

namespace allanlab::app {
namespace {

TEST(KalibrYaml, WritesDensitiesInSi) {
  KalibrGyroNoise noise;
  // 0.0267 deg/sqrt(h) = 7.767e-6 rad/s/sqrt(Hz); 0.03 deg/h/sqrt(h) = 2.424e-9 rad/s^2/sqrt(Hz).
  noise.noise_density.value = units::DegPerSqrtHour(0.0267);
  noise.random_walk.value = units::DegPerHourPerSqrtHour(0.03);
  noise.update_rate_hz = 400.0;
  Provenance p;
  p.command = "fit";
  const std::string yaml = KalibrImuYaml(noise, p);
  EXPECT_NEAR(units::DegPerSqrtHour(0.0267), 7.767e-6, 1e-9);
  EXPECT_NEAR(units::DegPerHourPerSqrtHour(0.03), 2.424e-9, 1e-12);
  EXPECT_NE(yaml.find("gyroscope_noise_density: " + ShortestDecimal(units::DegPerSqrtHour(0.0267))),
            std::string::npos)
      << yaml;
  EXPECT_NE(yaml.find("gyroscope_random_walk: "), std::string::npos);
  EXPECT_NE(yaml.find("update_rate: 400"), std::string::npos);
  EXPECT_NE(yaml.find("rad/s/sqrt(Hz)"), std::string::npos);
  EXPECT_EQ(yaml.find("WARNING"), std::string::npos);
}

TEST(KalibrYaml, UpperBoundsAndWarningSaySo) {
  KalibrGyroNoise noise;
  noise.noise_density.value = 1e-5;
  noise.random_walk = {2e-8, std::nullopt, true};
  noise.update_rate_hz = 100.0;
  noise.warning = "poor fit";
  const std::string yaml = KalibrImuYaml(noise, Provenance{});
  EXPECT_NE(yaml.find("# WARNING: poor fit"), std::string::npos) << yaml;
  EXPECT_NE(yaml.find("gyroscope_random_walk: 2e-08  # 95 % upper bound"), std::string::npos) << yaml;
}

}  // namespace
}  // namespace allanlab::app
