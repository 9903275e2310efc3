// End-to-end tests of `allanlab fit`: a simulated record with known coefficients, the JSON
// keys of `fit --json`, the Kalibr file, and clear refusals. The built binary runs in a fresh
// directory per test.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "tests/support/command_test.h"
#include "tests/support/read_file.h"

namespace allanlab::app {
namespace {

namespace fs = std::filesystem;

class FitCommandTest : public testing_support::CommandTest {
 protected:
  FitCommandTest() : CommandTest("allanlab_fit") {}
};

// A 2-hour N + B record (white and flicker only; Q, K, R absent) at 100 Hz as f64.
TEST_F(FitCommandTest, RecoversSimulatedCoefficientsAndWritesContracts) {
  std::ofstream(dir_ / "gyro.yaml") << "name: nb\nsample_rate: 100 Hz\nterms:\n"
                                       "  - {type: arw, N: 0.2 deg/sqrt(h)}\n"
                                       "  - {type: bias_instability, B: 3 deg/h}\n";
  ASSERT_EQ(Run("simulate --sensor " + Path("gyro.yaml") +
                " --duration 7200 --seed 5 --format f64 -o " + Path("rec.f64")),
            0)
      << Read("err.txt");
  ASSERT_EQ(Run("fit " + Path("rec.f64") + " --format f64 --rate 100 --units deg/s --json " +
                Path("fit.json") + " --kalibr " + Path("imu.yaml")),
            0)
      << Read("err.txt");
  const auto j = nlohmann::json::parse(Read("fit.json"));
  EXPECT_EQ(j["method"], "gls");
  for (const char* key : {"Q", "N", "B", "K", "R"})
    ASSERT_TRUE(j["coefficients"].contains(key)) << key;
  const auto& n = j["coefficients"]["N"];
  const auto& b = j["coefficients"]["B"];
  EXPECT_EQ(n["unit"], "deg/sqrt(h)");
  EXPECT_EQ(b["unit"], "deg/h");
  EXPECT_NEAR(n["value"].get<double>(), 0.2, 3.0 * n["sigma"].get<double>());
  EXPECT_NEAR(b["value"].get<double>(), 3.0, 3.0 * b["sigma"].get<double>());
  EXPECT_TRUE(j["fit"].contains("chi2") && j["fit"].contains("dof") &&
              j["fit"].contains("converged"));
  EXPECT_TRUE(j["bandwidth_hz"].contains("found"));
  EXPECT_TRUE(j["provenance"].contains("git_sha"));
  const std::string kalibr = Read("imu.yaml");
  EXPECT_NE(kalibr.find("gyroscope_noise_density:"), std::string::npos) << kalibr;
  EXPECT_NE(kalibr.find("update_rate: 100"), std::string::npos) << kalibr;
  EXPECT_NE(Read("out.txt").find("slope method"), std::string::npos);
}

TEST_F(FitCommandTest, RefusesBadInput) {
  std::ofstream(dir_ / "short.csv") << "t_s,x\n0,1\n0.01,2\n0.02,1.5\n0.03,1\n";
  EXPECT_EQ(Run("fit " + Path("missing.csv")), 1);
  EXPECT_NE(Read("err.txt").find("allanlab fit: error:"), std::string::npos) << Read("err.txt");
  EXPECT_EQ(Run("fit " + Path("short.csv") + " --method magic"), 2);
  EXPECT_NE(Read("err.txt").find("--method"), std::string::npos);
  EXPECT_EQ(Run("fit " + Path("short.csv") + " --terms N,X"), 2);
  EXPECT_NE(Read("err.txt").find("--terms"), std::string::npos);
  EXPECT_EQ(Run("fit " + Path("short.csv") + " --uncertainty magic"), 2);
  EXPECT_NE(Read("err.txt").find("--uncertainty"), std::string::npos);
  EXPECT_EQ(Run("fit " + Path("short.csv") + " --uncertainty bootstrap --bootstrap-trials 1"), 2);
  EXPECT_NE(Read("err.txt").find("--bootstrap-trials"), std::string::npos);
  EXPECT_EQ(Run("fit " + Path("short.csv") + " --units deg/s --json " + Path("j.json")), 1);
  EXPECT_FALSE(fs::exists(dir_ / "j.json"));  // no partial output
}

// --uncertainty bootstrap: the JSON says so and carries both sigmas; the same seed gives the
// same sigmas with one thread or two.
TEST_F(FitCommandTest, BootstrapUncertaintyIsLabelledAndDeterministic) {
  std::ofstream(dir_ / "gyro.yaml") << "name: nb\nsample_rate: 100 Hz\nterms:\n"
                                       "  - {type: arw, N: 0.2 deg/sqrt(h)}\n"
                                       "  - {type: bias_instability, B: 3 deg/h}\n";
  ASSERT_EQ(Run("simulate --sensor " + Path("gyro.yaml") +
                " --duration 600 --seed 5 --format f64 -o " + Path("rec.f64")),
            0)
      << Read("err.txt");
  const std::string fit = "fit " + Path("rec.f64") +
                          " --format f64 --rate 100 --terms N,B --no-select --uncertainty bootstrap "
                          "--bootstrap-trials 6 --seed 3 --json ";
  setenv("OMP_NUM_THREADS", "1", 1);
  const int single = Run(fit + Path("one.json"));
  unsetenv("OMP_NUM_THREADS");
  ASSERT_EQ(single, 0) << Read("err.txt");
  EXPECT_NE(Read("out.txt").find("uncertainty: parametric bootstrap (6 of 6"), std::string::npos)
      << Read("out.txt");
  setenv("OMP_NUM_THREADS", "2", 1);
  const int dual = Run(fit + Path("two.json"));
  unsetenv("OMP_NUM_THREADS");
  ASSERT_EQ(dual, 0) << Read("err.txt");
  const auto one = nlohmann::json::parse(Read("one.json"));
  const auto two = nlohmann::json::parse(Read("two.json"));
  EXPECT_EQ(one["uncertainty"]["method"], "bootstrap");
  EXPECT_EQ(one["uncertainty"]["replicates_used"], 6);
  for (const char* key : {"N", "B"}) {
    const auto& c = one["coefficients"][key];
    ASSERT_TRUE(c.contains("covariance_sigma") && c.contains("bootstrap_bias")) << key;
    EXPECT_GT(c["sigma"].get<double>(), 0.0) << key;
    EXPECT_EQ(c["sigma"], two["coefficients"][key]["sigma"]) << key;
  }
}

// The same simulated record written in rad/s and in deg/s fits to the same coefficients with no
// --units: the file states its unit. The old reader took rad/s as deg/s (N 57x too large).
TEST_F(FitCommandTest, ReadsTheUnitsTheRecordStates) {
  std::ofstream(dir_ / "gyro.yaml") << "name: nb\nsample_rate: 100 Hz\nterms:\n"
                                       "  - {type: arw, N: 0.2 deg/sqrt(h)}\n"
                                       "  - {type: bias_instability, B: 3 deg/h}\n";
  const std::string simulate =
      "simulate --sensor " + Path("gyro.yaml") + " --duration 600 --seed 5 ";
  ASSERT_EQ(Run(simulate + "--units deg/s -o " + Path("deg.csv")), 0) << Read("err.txt");
  ASSERT_EQ(Run(simulate + "--units rad/s -o " + Path("rad.csv")), 0) << Read("err.txt");
  ASSERT_EQ(Run(simulate + "--units rad/s --format f64 -o " + Path("rad.f64")), 0)
      << Read("err.txt");
  const std::string options = " --terms N,B --no-select --band-limit off --json ";
  ASSERT_EQ(Run("fit " + Path("deg.csv") + options + Path("deg.json")), 0) << Read("err.txt");
  ASSERT_EQ(Run("fit " + Path("rad.csv") + options + Path("rad.json")), 0) << Read("err.txt");
  ASSERT_EQ(Run("fit " + Path("rad.f64") + " --format f64" + options + Path("f64.json")), 0)
      << Read("err.txt");
  const auto deg = nlohmann::json::parse(Read("deg.json"));
  for (const std::string other : {"rad.json", "f64.json"}) {
    const auto j = nlohmann::json::parse(Read(other));
    for (const char* key : {"N", "B"}) {
      const double expected = deg["coefficients"][key]["value"].get<double>();
      EXPECT_NEAR(j["coefficients"][key]["value"].get<double>(), expected, 1e-6 * expected)
          << other << " " << key;
    }
  }
  EXPECT_NEAR(deg["coefficients"]["N"]["value"].get<double>(), 0.2, 0.02);
  EXPECT_EQ(Run("fit " + Path("rad.csv") + " --units deg/s"), 2);
  EXPECT_NE(Read("err.txt").find("--units (deg/s) contradicts column rate_rad_per_s (rad/s)"),
            std::string::npos)
      << Read("err.txt");
}

// 1 s at 100 Hz of white noise: the old fit reported R = 4.85e6 +- 0.48e6 deg/h^2 without a
// word. Five terms need 256 samples (app/input/record_support.h); one term is fine.
TEST_F(FitCommandTest, RefusesRecordsTooShortForTheTerms) {
  std::ofstream(dir_ / "white.yaml") << "name: white\nsample_rate: 100 Hz\nterms:\n"
                                        "  - {type: arw, N: 0.2 deg/sqrt(h)}\n";
  ASSERT_EQ(Run("simulate --sensor " + Path("white.yaml") + " --duration 1 --seed 2 -o " +
                Path("one.csv")),
            0)
      << Read("err.txt");
  EXPECT_EQ(Run("fit " + Path("one.csv") + " --json " + Path("j.json")), 1);
  const std::string err = Read("err.txt");
  EXPECT_NE(err.find("one.csv: 1 s (100 samples at 100 Hz) gives 4 octave tau(s) with at least "
                     "8 clusters (tau <= T/8); fitting 5 parameter(s) needs 6: record at least "
                     "2.56 s (256 samples), or fit fewer terms (--terms)"),
            std::string::npos)
      << err;
  EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
  EXPECT_FALSE(fs::exists(dir_ / "j.json"));
  EXPECT_EQ(Run("fit " + Path("one.csv") + " --terms N --band-limit off"), 0) << Read("err.txt");
}

// fit --curve: a published curve, here the closed-form white-noise ADEV N / sqrt(tau) (N = 0.3
// deg/sqrt(h) = 18 deg/h at 1 s) as deviations in deg/h and as variances in (rad/s)^2; the fit
// gives N back. Noise-free, so only the fit's convergence limits the agreement.
TEST_F(FitCommandTest, FitsAPublishedCurve) {
  std::ofstream table(dir_ / "curve.csv");
  table << "# published curve\ntau_s,adev_x,avar\n";
  for (double tau = 0.01; tau < 10000; tau *= 2) {
    const double adev_deg_h = 18.0 / std::sqrt(tau);
    const double adev_rad_s = adev_deg_h * M_PI / 180.0 / 3600.0;
    char row[128];
    std::snprintf(row, sizeof row, "%.17g,%.17g,%.17g\n", tau, adev_deg_h, adev_rad_s * adev_rad_s);
    table << row;
  }
  table.close();
  const std::string common = " --record-length 7200 --rate 100 --terms N,B --no-select --band-limit off --json ";
  ASSERT_EQ(Run("fit --curve " + Path("curve.csv") + common + Path("dev.json")), 0) << Read("err.txt");
  // Rows from 5242.88 s on lie beyond half the 7200 s record: named, not used.
  EXPECT_NE(Read("err.txt").find(" s is beyond half the record (7200 s); row not used"),
            std::string::npos)
      << Read("err.txt");
  ASSERT_EQ(Run("fit --curve " + Path("curve.csv") + " --curve-column avar --curve-units rad/s" +
                common + Path("var.json")),
            0)
      << Read("err.txt");
  for (const char* name : {"dev.json", "var.json"}) {
    const auto j = nlohmann::json::parse(Read(name));
    EXPECT_NEAR(j["coefficients"]["N"]["value"].get<double>(), 0.3, 1e-6) << name;
    EXPECT_NE(j["provenance"]["curve"].get<std::string>().find("record 7200 s at 100 Hz"),
              std::string::npos);
  }
  EXPECT_EQ(Run("fit --curve " + Path("curve.csv") + " --rate 100"), 2);
  EXPECT_NE(Read("err.txt").find("--curve needs --record-length S > 0 and --rate HZ > 0"),
            std::string::npos);
  EXPECT_EQ(Run("fit " + Path("curve.csv") + " --curve " + Path("curve.csv") +
                " --record-length 7200 --rate 100"),
            2);
  EXPECT_EQ(Run("fit"), 2);
  EXPECT_EQ(Run("fit --curve " + Path("curve.csv") + " --curve-column adev_q --record-length 7200 --rate 100"), 2);
  EXPECT_NE(Read("err.txt").find("the header needs a tau column (tau_s or tau) and adev_q"),
            std::string::npos)
      << Read("err.txt");
}

}  // namespace
}  // namespace allanlab::app
