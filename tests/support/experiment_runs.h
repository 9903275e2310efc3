#pragma once
// Small sweeps for experiment tests, run in-process without the runner: every (point, trial) in
// order through one workspace, as the runner's rows would be (header-only: the support library
// does not link experiments/).
#include <cmath>
#include <cstdint>
#include <string>

#include <gtest/gtest.h>

#include "experiments/runner.h"
#include "experiments/trial_driver.h"
#include "sim/sensor_spec.h"

namespace allanlab::testing_support {

inline experiments::RunSummary RunSweepInline(const experiments::SweepSpec& spec,
                                              const experiments::TrialDriver& driver) {
  experiments::RunSummary run;
  auto workspace = driver.MakeWorkspace();
  for (const experiments::SweepPoint& point : spec.points) {
    run.columns.push_back(driver.Columns(spec, point));
    for (std::int64_t t = 0; t < spec.trials; ++t) {
      experiments::TrialRow row;
      row.point = point.index;
      row.trial = t;
      row.values = driver.Run(spec, point, t, workspace.get());
      EXPECT_EQ(row.values.size(), run.columns.back().size());
      run.rows.push_back(row);
    }
  }
  run.ok = true;
  return run;
}

// A preset at another output rate and length, as a sweep's record.sample_rate / duration make it.
inline experiments::SweepPoint PresetPoint(const std::string& preset, double rate_hz,
                                           double duration_s, int index) {
  experiments::SweepPoint p;
  std::string why;
  EXPECT_TRUE(sim::LoadPreset(preset, &p.model, &why)) << why;
  p.index = index;
  p.model.sample_clock = SampleClock::FromRateHz(rate_hz);
  p.num_samples = static_cast<std::int64_t>(std::llround(rate_hz * duration_s));
  return p;
}

}  // namespace allanlab::testing_support
