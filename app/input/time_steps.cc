#include "app/input/time_steps.h"

#include <cmath>

#include "common/number_text.h"

namespace allanlab::app {

bool TimeSteps::AddStep(double time_s, std::int64_t line, std::string* why) {
  line += line_offset_;
  if (!std::isfinite(time_s)) {
    if (why)
      *why = position_ + " " + std::to_string(line) + ": time " + ShortestDecimal(time_s) +
             " is not a finite number";
    return false;
  }
  if (samples_ > 0) {
    const double step = time_s - previous_s_;
    if (!(step > 0.0)) {
      if (why) {
        *why = "time is not increasing: " + position_ + " " + std::to_string(line) +
               " has t = " + ShortestDecimal(time_s) +
               " s after t = " + ShortestDecimal(previous_s_) + " s at " + position_ + " " +
               std::to_string(previous_line_) + " (sort the record first)";
      }
      return false;
    }
    if (samples_ == 1 || step > largest_) {
      largest_ = step;
      largest_line_ = line;
    }
    if (samples_ == 1 || step < smallest_) {
      smallest_ = step;
      smallest_line_ = line;
    }
    bool placed = false;
    for (Group& g : groups_) {
      // |step - mean| <= tolerance * mean, times count: no division per row.
      const double count = static_cast<double>(g.count);
      if (std::abs(step * count - g.sum_s) <= kStepTolerance * g.sum_s) {
        g.sum_s += step;
        ++g.count;
        placed = true;
        break;
      }
    }
    if (!placed) {
      if (static_cast<int>(groups_.size()) < kMaxGroups) {
        groups_.push_back({step, 1});
      } else {
        ++ungrouped_;
      }
    }
  }
  previous_s_ = time_s;
  previous_line_ = line;
  ++samples_;
  return true;
}

TimeSteps::Summary TimeSteps::Summarize() const {
  Summary s;
  s.samples = samples_;
  s.position = position_;
  if (samples_ < 2) return s;
  const Group* best = &groups_.front();
  for (const Group& g : groups_) {
    if (g.count > best->count) best = &g;
  }
  s.nominal_step_s = best->mean();
  s.irregular_steps = (samples_ - 1) - best->count;
  s.largest_step_s = largest_;
  s.largest_step_line = largest_line_;
  s.smallest_step_s = smallest_;
  s.smallest_step_line = smallest_line_;
  return s;
}

std::string TimeSteps::Describe(const Summary& s, const std::string& column) {
  // Steps are differences of printed times: their last digits are noise, not information.
  const auto seconds = [](double v) { return SignificantDigits(v, 6) + " s"; };
  std::string out = std::to_string(s.irregular_steps) + " irregular time step(s) in " + column +
                    " (nominal " + seconds(s.nominal_step_s);
  if (s.largest_step_s > s.nominal_step_s * (1 + kStepTolerance)) {
    out += "; largest " + seconds(s.largest_step_s) + " at " + s.position + " " +
           std::to_string(s.largest_step_line);
  }
  if (s.smallest_step_s < s.nominal_step_s * (1 - kStepTolerance)) {
    out += "; smallest " + seconds(s.smallest_step_s) + " at " + s.position + " " +
           std::to_string(s.smallest_step_line);
  }
  return out + ")";
}

}  // namespace allanlab::app
