#pragma once
// `diagnose` progress on stderr: the stage the diagnosis is in, its steps done, the time so far
// and an estimate of the stage's time left. On a terminal one line rewritten in place and cleared
// when done; when stderr is not a terminal nothing, unless asked (--progress): then one line per
// stage change or every few seconds. Never under --quiet.
#include <chrono>
#include <string>
#include <string_view>

namespace allanlab::app {

class DiagnoseProgress {
 public:
  // `label`: what is diagnosed ("Gyro_X", a file name); `enabled`: false under --quiet;
  // `off_terminal`: shown also when stderr is not a terminal (--progress).
  DiagnoseProgress(std::string label, bool enabled, bool off_terminal = false);
  ~DiagnoseProgress();
  DiagnoseProgress(const DiagnoseProgress&) = delete;
  DiagnoseProgress& operator=(const DiagnoseProgress&) = delete;
  // experiments::DiagnoseOptions::progress.
  void Update(std::string_view stage, int done, int total);
  void Clear();

 private:
  using Clock = std::chrono::steady_clock;
  std::string label_;
  bool enabled_;
  bool lines_;  // whole lines (stderr is not a terminal), not one line rewritten in place
  bool shown_ = false;
  std::string stage_;
  Clock::time_point start_, stage_start_, last_;
};

}  // namespace allanlab::app
