#include "experiments/progress.h"

#include <unistd.h>

#include <cstdio>

namespace allanlab::experiments {

bool StderrIsTerminal() { return ::isatty(STDERR_FILENO) == 1; }

ProgressMeter::ProgressMeter(bool enabled, std::int64_t total, std::int64_t already_done)
    : enabled_(enabled),
      terminal_(StderrIsTerminal()),
      total_(total),
      already_done_(already_done),
      start_(std::chrono::steady_clock::now()),
      last_(start_) {}

void ProgressMeter::Update(std::int64_t done) {
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  const auto interval = terminal_ ? std::chrono::milliseconds(250) : std::chrono::seconds(5);
  if (now - last_ < interval) return;
  last_ = now;
  Print(done, false);
}

void ProgressMeter::Finish(std::int64_t done) {
  if (enabled_) Print(done, true);
}

void ProgressMeter::Print(std::int64_t done, bool final) {
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const double rate = elapsed > 0.0 ? static_cast<double>(done) / elapsed : 0.0;
  const double eta = rate > 0.0 ? static_cast<double>(total_ - done) / rate : 0.0;
  const std::int64_t all = total_ + already_done_;
  std::fprintf(stderr, "%ssweep: %lld/%lld trials (%.1f%%), %.3g trials/s, %s %.0f s%s",
               terminal_ ? "\r" : "", static_cast<long long>(done + already_done_),
               static_cast<long long>(all),
               all > 0 ? 100.0 * static_cast<double>(done + already_done_) / static_cast<double>(all)
                       : 100.0,
               rate, final ? "took" : "ETA", final ? elapsed : eta,
               terminal_ && !final ? "   " : "\n");
  std::fflush(stderr);
}

}  // namespace allanlab::experiments
