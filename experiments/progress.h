#pragma once
// Progress lines on stderr for long sweeps: done/total, trials/s, ETA. On a terminal the line is
// rewritten in place a few times a second; elsewhere (when forced) a new line every few seconds.
#include <chrono>
#include <cstdint>

namespace allanlab::experiments {

class ProgressMeter {
 public:
  // `enabled`: print at all; `total`: trials to compute in this run (resumed ones excluded).
  ProgressMeter(bool enabled, std::int64_t total, std::int64_t already_done);
  // Called (from one thread at a time) with the trials computed so far in this run.
  void Update(std::int64_t done);
  void Finish(std::int64_t done);

 private:
  void Print(std::int64_t done, bool final);
  bool enabled_;
  bool terminal_;
  std::int64_t total_;
  std::int64_t already_done_;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point last_;
};

// True when stderr is a terminal (progress is then on by default).
bool StderrIsTerminal();

}  // namespace allanlab::experiments
