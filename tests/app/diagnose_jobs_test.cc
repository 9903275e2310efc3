// `allanlab diagnose --jobs N`: the candidates run in parallel, and the JSON is the same for one
// thread and two (every simulated record is drawn from (seed, trial), results are kept in effect
// order).
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "sim/sensor_model.h"
#include "tests/support/command_test.h"

namespace allanlab::app {
namespace {

class DiagnoseJobsTest : public testing_support::CommandTest {
 protected:
  DiagnoseJobsTest() : CommandTest("allanlab_diagnose_jobs", "diagnose") {}
};

TEST_F(DiagnoseJobsTest, SameJsonForOneAndTwoThreads) {
  // White rate noise (1e-4 rad/s per sample) with a 6e-5 rad/s step at 60 % of the record (16384 samples): the
  // block means (1024 samples: sd 3e-6 rad/s) see it at ~20 sigma against a white-noise baseline,
  // so the candidates all run.
  sim::SensorModel model;
  model.sample_rate_hz = 100.0;
  sim::WhiteRateNoise white;
  white.arw_rad_per_sqrt_s = 1e-5;
  model.terms = {white};
  const std::vector<double> rate = model.Generate(3, 0, 16384);
  {
    std::ofstream out(dir_ / "rec.csv");
    out << "rate_rad_per_s\n";
    for (std::size_t k = 0; k < rate.size(); ++k) out << rate[k] + (k >= 9830 ? 6e-5 : 0.0) << "\n";
  }
  nlohmann::json runs[2];
  for (int jobs = 1; jobs <= 2; ++jobs) {
    std::ostringstream args;
    args << Path("rec.csv") << " --rate 100 --model N --trials 5 --jobs " << jobs << " --json " << Path("d.json");
    ASSERT_EQ(Run(args.str()), 0) << Read("err.txt");
    runs[jobs - 1] = nlohmann::json::parse(Read("d.json"));
    runs[jobs - 1].erase("provenance");
  }
  ASSERT_TRUE(runs[0]["gap"]["significant"].get<bool>()) << runs[0].dump(1);
  ASSERT_GE(runs[0]["candidates"].size(), 2u);
  EXPECT_EQ(runs[0].dump(), runs[1].dump());
  EXPECT_EQ(Run(Path("rec.csv") + " --rate 100 --jobs -1"), 2);
}

}  // namespace
}  // namespace allanlab::app
