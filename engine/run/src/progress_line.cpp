#include "run/progress_line.hpp"

#include <algorithm>
#include <cstdio>

namespace rumble {

void ProgressLine::update(double t) {
  if (!enabled_) return;
  const double elapsed = std::chrono::duration<double>(Clock::now() - start_).count();
  if (elapsed - last_ < 0.25 && t < t_end_) return;
  last_ = elapsed;
  const double fraction = std::min(1.0, t / t_end_);
  const double eta = fraction > 0.0 ? elapsed * (1.0 - fraction) / fraction : 0.0;
  std::fprintf(stderr, "\r  t = %.4f / %.4f s  %3.0f%%  elapsed %.1f s  ETA %.1f s   ", t, t_end_,
               100.0 * fraction, elapsed, eta);
  std::fflush(stderr);
  shown_ = true;
}

ProgressLine::~ProgressLine() {
  if (shown_) std::fprintf(stderr, "\n");
}

}  // namespace rumble
