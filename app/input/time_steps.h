#pragma once
// The sample period read from a time column, in one pass and bounded memory, with the steps that
// do not fit it counted rather than ignored (a gap of missing samples, a stall, jitter).
//
// Steps are grouped: a step joins a group when it is within kStepTolerance (relative) of the
// group's mean step. The group with the most steps is the nominal period; every other step is
// irregular. Only the first kMaxGroups distinct groups are kept (later odd steps still count as
// irregular), so a file with wild timestamps costs no memory.
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace allanlab::app {

class TimeSteps {
 public:
  static constexpr double kStepTolerance = 1e-3;
  static constexpr int kMaxGroups = 64;

  // What a position is called in messages, and its number for line L: "line" and L (a text
  // file), or "message" and L - 1 (a ROS bag's messages, after the header line of their text).
  TimeSteps() = default;
  TimeSteps(std::string position, std::int64_t line_offset)
      : position_(std::move(position)), line_offset_(line_offset) {}

  // Adds the time of the next sample (seconds) read at `line`. Fails (with the line numbers) when
  // the time is not finite or not strictly greater than the previous one.
  bool Add(double time_s, std::int64_t line, std::string* why) {
    // Nearly every step of a long record: no new extreme, within the first group. What the
    // general case would do for it, inline (it is paid per row).
    if (samples_ > 1 && std::isfinite(time_s)) {
      const double step = time_s - previous_s_;
      Group& g = groups_.front();
      if (step > 0.0 && step <= largest_ && step >= smallest_ &&
          std::abs(step * static_cast<double>(g.count) - g.sum_s) <= kStepTolerance * g.sum_s) {
        g.sum_s += step;
        ++g.count;
        previous_s_ = time_s;
        previous_line_ = line + line_offset_;
        ++samples_;
        return true;
      }
    }
    return AddStep(time_s, line, why);
  }

  struct Summary {
    std::int64_t samples = 0;
    double nominal_step_s = 0.0;         // mean of the steps in the largest group (0: < 2 samples)
    std::int64_t irregular_steps = 0;    // steps outside that group
    double largest_step_s = 0.0;         // the worst gap
    std::int64_t largest_step_line = 0;  // line of the sample that ends it
    double smallest_step_s = 0.0;
    std::int64_t smallest_step_line = 0;
    std::string position = "line";  // what *_line counts
  };
  Summary Summarize() const;

  // "2 irregular time step(s) in t (nominal 0.1 s; largest 1.1 s at line 102)", with the
  // smallest step too when it is off the nominal period; times to 6 significant digits.
  static std::string Describe(const Summary& summary, const std::string& column);

 private:
  bool AddStep(double time_s, std::int64_t line, std::string* why);
  struct Group {
    double sum_s = 0.0;
    std::int64_t count = 0;
    double mean() const { return sum_s / static_cast<double>(count); }
  };
  std::string position_ = "line";
  std::int64_t line_offset_ = 0;
  std::vector<Group> groups_;
  std::int64_t samples_ = 0;
  std::int64_t ungrouped_ = 0;
  double previous_s_ = 0.0;
  std::int64_t previous_line_ = 0;
  double largest_ = 0.0, smallest_ = 0.0;
  std::int64_t largest_line_ = 0, smallest_line_ = 0;
};

}  // namespace allanlab::app
