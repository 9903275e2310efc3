// `allanlab avar` on a real recording: ADIS16405 imu1, Gyro_X (deg/s, 100 Hz, 10^6 samples),
// overlapping AVAR at the 18 octave taus of the R package avar's reference (SMAC-Group, file
// imu1_oavar_reference.csv; see SOURCE.txt beside it; CC BY-NC-SA 4.0, read in place, not copied).
//
// Two checks:
//  1. Against the exact value. Every Gyro_X value is a multiple of 0.05 deg/s, so 20 x value is an
//     integer and the OAVAR is a ratio of integers, computed here without rounding; the command
//     must match it to 1e-12 relative.
//  2. Against the published reference. That file is itself off the exact value by up to 5.9e-6
//     relative (largest at tau = 40.96 s; measured with the integer computation above; its
//     rounding, not a different formula: the error is not smooth in tau), so the tolerance is
//     1e-5, not the 1e-6 first asked for: no correct estimator can meet 1e-6 against it.
//
// The data directory is $ALLANLAB_DATA_DIR, else ../shared/data beside the repository; the test
// skips with a message when it is absent (a clean clone may not have it; CI does).
#include <gtest/gtest.h>
#include <stdlib.h>
#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "app/reports/provenance.h"
#include "app/input/record_reader.h"
#include "common/number_text.h"
#include "tests/support/read_file.h"

namespace allanlab::app {
namespace {

namespace fs = std::filesystem;

fs::path DataDir() {
  if (const char* env = std::getenv("ALLANLAB_DATA_DIR"); env && *env) return env;
  // ALLANLAB_TEST_DATA_DIR is <repo>/tests/data.
  return fs::path(ALLANLAB_TEST_DATA_DIR).parent_path().parent_path().parent_path() / "shared" /
         "data";
}

using testing_support::ReadAll;

// tau [s] -> avar [(deg/s)^2] for one channel of the reference file.
std::map<double, double> Reference(const fs::path& path, const std::string& channel) {
  std::map<double, double> out;
  std::istringstream in(ReadAll(path));
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#' || line.rfind("channel,", 0) == 0) continue;
    std::istringstream fields(line);
    std::string name, tau, avar;
    std::getline(fields, name, ',');
    std::getline(fields, tau, ',');
    std::getline(fields, avar, ',');
    if (name == channel) out[std::stod(tau)] = std::stod(avar);
  }
  return out;
}

// OAVAR of 0.05-quantised values, exactly: integer prefix sums, 128-bit sum of squares.
double ExactOavar(const std::vector<std::int64_t>& twentieths, std::int64_t m) {
  const auto n = static_cast<std::int64_t>(twentieths.size());
  std::vector<std::int64_t> s(twentieths.size() + 1, 0);
  for (std::int64_t k = 0; k < n; ++k) s[k + 1] = s[k] + twentieths[k];
  unsigned __int128 sum = 0;
  for (std::int64_t t = 0; t + 2 * m <= n; ++t) {
    const std::int64_t d = s[t + 2 * m] - 2 * s[t + m] + s[t];
    sum += static_cast<unsigned __int128>(d * d);
  }
  const long double terms = static_cast<long double>(n - 2 * m + 1);
  return static_cast<double>(static_cast<long double>(sum) / (2.0L * m * m * terms * 400.0L));
}

TEST(Adis16405AvarRefTest, OverlappingGyroXMatchesExactValueAndPublishedReference) {
  const fs::path dir = DataDir() / "real" / "adis16405";
  const fs::path record = dir / "adis_16405_imu1.csv.xz";
  const fs::path reference = dir / "imu1_oavar_reference.csv";
  if (!fs::exists(record) || !fs::exists(reference)) {
    GTEST_SKIP() << "real-data set not found at " << dir
                 << " (set ALLANLAB_DATA_DIR to the shared data directory)";
  }
  const std::map<double, double> ref = Reference(reference, "Gyro_X");
  ASSERT_EQ(ref.size(), 18u);
  std::string taus;
  for (const auto& [tau, avar] : ref) taus += (taus.empty() ? "" : ",") + ShortestDecimal(tau);

  const fs::path out = fs::path(::testing::TempDir()) / "adis16405_avar_ref.json";
  const std::string command = std::string("'") + ALLANLAB_BINARY + "' avar '" + record.string() +
                              "' --column Gyro_X --units deg/s --out-units deg/s --estimator "
                              "overlapping --ci none --taus " +
                              taus + " --json '" + out.string() + "' > /dev/null";
  const int status = std::system(command.c_str());
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << command;
  const nlohmann::json j = nlohmann::json::parse(ReadAll(out));
  fs::remove(out);
  EXPECT_EQ(j["input"]["rate_samples"], 1000000);
  EXPECT_EQ(j["input"]["sample_rate_hz"], 100.0);
  ASSERT_EQ(j["points"].size(), 18u) << j["dropped"].dump();

  // The same record through the reader, as integers in units of 0.05 deg/s.
  RecordReaderOptions read;
  read.path = record.string();
  read.column = "Gyro_X";
  read.units = "deg/s";  // the file names no unit (data/real/adis16405: deg/s)
  std::vector<double> values;
  RecordInfo info;
  RecordError error;
  ASSERT_TRUE(ReadRecordValues(read, &values, &info, &error)) << error.message;
  std::vector<std::int64_t> twentieths;
  for (double v : values) {
    const double scaled = v * 20.0;
    ASSERT_LT(std::abs(scaled - std::round(scaled)), 1e-9) << v << " is not a multiple of 0.05";
    twentieths.push_back(static_cast<std::int64_t>(std::llround(scaled)));
  }

  double worst_vs_reference = 0.0;
  for (const auto& p : j["points"]) {
    const double tau = p["tau_s"].get<double>();
    const std::int64_t m = p["m"].get<std::int64_t>();
    const double ours = p["var"].get<double>();
    const double exact = ExactOavar(twentieths, m);
    EXPECT_NEAR(ours, exact, 1e-12 * exact) << "tau = " << tau << " s: command vs exact";
    const auto it = ref.find(tau);
    ASSERT_NE(it, ref.end()) << "tau " << tau << " not in the reference";
    EXPECT_NEAR(ours, it->second, 1e-5 * it->second) << "tau = " << tau << " s vs reference";
    worst_vs_reference = std::max(worst_vs_reference, std::abs(ours / it->second - 1));
  }
  std::cout << "largest relative difference to the R avar reference: " << worst_vs_reference
            << "\n";
}

}  // namespace
}  // namespace allanlab::app
