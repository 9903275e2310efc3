// `allanlab fit` with its defaults on records where one term cannot be pinned by the data: 2 h at
// 100 Hz of N = 0.17 deg/sqrt(h), B = 3 deg/h and K = 5 or 3 deg/h/sqrt(h). Rate ramp and rate
// random walk compete for the longest taus there; backward elimination once dropped K because R
// had taken its place ("K 0 +- 0") and the Kalibr file then said gyroscope_random_walk: 0.
//
// The records come from a generator written here, apart from sim/: the rate is produced at 4x the
// output rate and averaged in blocks of 4 (a first-order-hold view sim/ does not use);
//   white rate: independent Gaussian samples of variance N^2 fs_internal, which averaged to the
//     output rate keep the density N;
//   rate random walk: the cumulative sum of Gaussian steps of variance K^2 / fs_internal;
//   flicker: a sum of first-order Gauss-Markov processes with time constants spaced 4 per decade
//     from 1 ms to 10x the record, each of variance B^2 d / pi with d = ln(10) / 4: their summed
//     one-sided PSD is B^2 / (pi f) between the extreme corners (IEEE 952's B^2 / (2 pi f) is
//     two-sided: its AVAR integral carries the factor 4, so AVAR = 2 ln2 B^2 / pi), with a ripple of about 4 e^(-pi^2 / d) ~ 2e-7 relative (the Poisson sum of the
//     log-spaced kernel 1 / (2 cosh ln(2 pi f tc)) ). The AVAR of 1/f noise at tau only sees the PSD around 1/tau, so
//     over 0.01 s .. 3600 s this approximation's AVAR is within the record's scatter of the
//     IEEE flicker law.
// What must hold on every record: no coefficient reported as 0 with sigma 0, each given by a value
// or a positive upper limit, the Kalibr random walk never 0. And N, B and K inside their reported
// 95 % intervals or under their 95 % upper limits as often as 95 % ranges should: the count over
// the 6 records' 18 checks within the lower acceptance band of Binomial(18, 0.95) at level 1e-3
// (tests/estimators/fit/profile_coverage_stat_test.cc measures the rates on many records). Each
// check is a 95 % event: asserted one by one on two fixed seeds, K = 5 on seed 11 fell above its
// limit (3.89) once the subsets were scored by the likelihood, the 1 in 20 a calibrated limit
// allows. The old backward elimination fails every record (K "0 +- 0", gyroscope_random_walk: 0).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "tests/support/command_test.h"
#include "tests/support/coverage_band.h"

namespace allanlab::app {
namespace {

constexpr double kDegPerRad = 180.0 / std::numbers::pi;

// Rate samples [deg/s] at fs_hz: N [deg/sqrt(h)], B [deg/h], K [deg/h/sqrt(h)].
std::vector<double> IndependentRecord(double fs_hz, double duration_s, double n_deg_rt_h,
                                      double b_deg_h, double k_deg_h_rt_h, std::uint64_t seed) {
  constexpr int kOversampling = 4;
  const double fs = fs_hz * kOversampling, dt = 1.0 / fs;
  // SI: rad/sqrt(s), rad/s, rad/s/sqrt(s).
  const double n = n_deg_rt_h / kDegPerRad / 60.0;
  const double b = b_deg_h / kDegPerRad / 3600.0;
  const double k = k_deg_h_rt_h / kDegPerRad / 3600.0 / 60.0;
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g(0.0, 1.0);
  const double d = std::log(10.0) / 4.0;
  std::vector<double> tc, phi, drive, state;
  for (double t = 1e-3; t < 10.0 * duration_s; t *= std::exp(d)) {
    tc.push_back(t);
    phi.push_back(std::exp(-dt / t));
    const double var = b * b * d / std::numbers::pi;
    drive.push_back(std::sqrt(var * (1.0 - phi.back() * phi.back())));
    state.push_back(std::sqrt(var) * g(rng));  // stationary start
  }
  const auto out = static_cast<std::int64_t>(duration_s * fs_hz);
  std::vector<double> y(static_cast<std::size_t>(out));
  double walk = 0.0;
  for (std::int64_t i = 0; i < out; ++i) {
    double sum = 0.0;
    for (int j = 0; j < kOversampling; ++j) {
      double v = n * std::sqrt(fs) * g(rng);
      walk += k * std::sqrt(dt) * g(rng);
      v += walk;
      for (std::size_t q = 0; q < tc.size(); ++q) {
        state[q] = phi[q] * state[q] + drive[q] * g(rng);
        v += state[q];
      }
      sum += v;
    }
    y[static_cast<std::size_t>(i)] = sum / kOversampling * kDegPerRad;
  }
  return y;
}

class FitMaskingTest : public testing_support::CommandTest {
 protected:
  FitMaskingTest() : CommandTest("allanlab_fit_masking") {}
};

TEST_F(FitMaskingTest, EveryTrueCoefficientInsideItsIntervalOrUnderItsLimit) {
  struct Case {
    double k;
    std::uint64_t seed;
  };
  int checks = 0, held = 0;
  for (const Case c : {Case{5.0, 11}, Case{3.0, 12}, Case{5.0, 13}, Case{3.0, 14}, Case{5.0, 15}, Case{3.0, 16}}) {
    SCOPED_TRACE("K = " + std::to_string(c.k));
    const std::vector<double> y = IndependentRecord(100.0, 7200.0, 0.17, 3.0, c.k, c.seed);
    {
      std::ofstream f(dir_ / "rec.f64", std::ios::binary);
      f.write(reinterpret_cast<const char*>(y.data()), static_cast<std::streamsize>(y.size() * sizeof(double)));
    }
    ASSERT_EQ(Run("fit " + Path("rec.f64") + " --format f64 --rate 100 --units deg/s --json " +
                  Path("fit.json") + " --kalibr " + Path("imu.yaml")),
              0)
        << Read("err.txt");
    const auto j = nlohmann::json::parse(Read("fit.json"));
    SCOPED_TRACE("fit printed:\n" + Read("out.txt"));
    const std::pair<const char*, double> truth[] = {{"N", 0.17}, {"B", 3.0}, {"K", c.k}};
    for (const auto& [id, value] : truth) {
      const auto& e = j["coefficients"][id];
      SCOPED_TRACE(std::string(id) + ": " + e.dump());
      ++checks;
      if (e.contains("upper_limit")) {
        EXPECT_FALSE(e["fitted"].get<bool>());
        EXPECT_GT(e["upper_limit"].get<double>(), 0.0);
        held += value <= e["upper_limit"].get<double>();
      } else {
        ASSERT_TRUE(e["fitted"].get<bool>()) << "neither a value nor an upper limit";
        ASSERT_TRUE(e.contains("interval_95"));
        held += e["interval_95"][0].get<double>() <= value && value <= e["interval_95"][1].get<double>();
      }
    }
    for (const auto& [id, e] : j["coefficients"].items()) {
      if (!e.contains("value") || !e.contains("sigma")) continue;  // parametric entries
      if (e["value"].is_null()) {
        EXPECT_TRUE(e.contains("upper_limit")) << id << ": no value and no upper limit";
        continue;
      }
      EXPECT_FALSE(e["value"].get<double>() == 0.0 && e["sigma"].get<double>() == 0.0)
          << id << " reported as 0 +- 0: " << e.dump();
    }
    const std::string table = Read("out.txt");
    EXPECT_EQ(table.find("dropped by term selection: removing it raises chi2 by 0"), std::string::npos) << table;
    const std::string kalibr = Read("imu.yaml");
    const auto at = kalibr.find("gyroscope_random_walk: ");
    ASSERT_NE(at, std::string::npos) << kalibr;
    EXPECT_GT(std::stod(kalibr.substr(at + 23)), 0.0) << kalibr;
  }
  const int lo = testing_support::CoverageBand(checks, 0.95, 1e-3, true).lo;
  std::printf("truth inside its 95 %% range or under its limit: %d of %d (band >= %d)\n", held, checks, lo);
  EXPECT_GE(held, lo);
}

}  // namespace
}  // namespace allanlab::app
