// The progress line of a long run on a terminal: simulated time, percentage, elapsed time and
// ETA, redrawn at most four times a second on stderr; off when not a terminal.
#pragma once

#include <chrono>

namespace rumble {

class ProgressLine {
 public:
  ProgressLine(bool enabled, double t_end) : enabled_(enabled), t_end_(t_end) {}
  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;
  ~ProgressLine();
  /// The run has reached simulated time t [s].
  void update(double t);

 private:
  using Clock = std::chrono::steady_clock;
  bool enabled_;
  double t_end_;  // s
  Clock::time_point start_ = Clock::now();
  double last_ = -1.0;  // s of wall time at the last redraw
  bool shown_ = false;
};

}  // namespace rumble
