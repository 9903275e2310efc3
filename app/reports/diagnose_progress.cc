#include "app/reports/diagnose_progress.h"

#include <cstdio>

#include "experiments/progress.h"

namespace allanlab::app {

DiagnoseProgress::DiagnoseProgress(std::string label, bool enabled, bool off_terminal)
    : label_(std::move(label)),
      enabled_(enabled && (off_terminal || experiments::StderrIsTerminal())),
      lines_(!experiments::StderrIsTerminal()),
      start_(Clock::now()),
      stage_start_(start_),
      last_(start_ - std::chrono::seconds(1)) {}

DiagnoseProgress::~DiagnoseProgress() { Clear(); }

void DiagnoseProgress::Update(std::string_view stage, int done, int total) {
  if (!enabled_) return;
  const Clock::time_point now = Clock::now();
  if (stage != stage_) {
    stage_ = stage;
    stage_start_ = now;
  } else if (now - last_ < (lines_ ? std::chrono::milliseconds(5000) : std::chrono::milliseconds(200)) && done < total) {
    return;
  }
  last_ = now;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double in_stage = std::chrono::duration<double>(now - stage_start_).count();
  std::string line = "diagnose " + label_ + ": " + std::string(stage);
  char buffer[96];
  if (total > 0) {
    std::snprintf(buffer, sizeof buffer, " %d/%d", done, total);
    line += buffer;
  }
  std::snprintf(buffer, sizeof buffer, ", %.0f s", elapsed);
  line += buffer;
  if (total > 0 && done > 0 && done < total) {
    std::snprintf(buffer, sizeof buffer, ", about %.0f s left in this stage", in_stage * (total - done) / done);
    line += buffer;
  }
  if (lines_) {
    std::fprintf(stderr, "%s\n", line.c_str());
  } else {
    std::fprintf(stderr, "\r%-78s", line.c_str());
    shown_ = true;
  }
  std::fflush(stderr);
}

void DiagnoseProgress::Clear() {
  if (!shown_) return;
  std::fprintf(stderr, "\r%78s\r", "");
  std::fflush(stderr);
  shown_ = false;
}

}  // namespace allanlab::app
