#pragma once
// `diagnose` progress on stderr: the stage the diagnosis is in, its steps done, the time so far
// and an estimate of the stage's time left, on one line rewritten in place. Only on a terminal
// (nothing when stderr is redirected) and not under --quiet; the line is cleared when done.
#include <chrono>
#include <string>
#include <string_view>

namespace allanlab::app {

class DiagnoseProgress {
 public:
  // `label`: what is diagnosed ("Gyro_X", a file name); `enabled`: false under --quiet.
  DiagnoseProgress(std::string label, bool enabled);
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
  bool shown_ = false;
  std::string stage_;
  Clock::time_point start_, stage_start_, last_;
};

}  // namespace allanlab::app
