#include "time/thread_tuner.hpp"

#include <algorithm>
#include <sstream>

namespace rumble::fem {

void ThreadTuner::grant(unsigned granted) {
  granted = std::max(1u, granted);
  if (!sizes_.empty() && sizes_.front() == granted) return;
  sizes_.clear();
  for (unsigned n = granted; n > 1; n /= 2) sizes_.push_back(n);
  sizes_.push_back(1);
  mean_.assign(sizes_.size(), 0.0);
  seconds_on_.assign(sizes_.size(), 0.0);
  current_ = chosen_ = 0;
  trying_ = sizes_.size() > 1;
  warm_up_ = kWarmUpSteps;
  steps_ = 0;
  trial_seconds_ = 0.0;
  held_ = 0.0;
  hold_ = kFirstHold;
}

void ThreadTuner::record(double seconds) {
  seconds_on_[current_] += seconds;
  if (!trying_) {
    held_ += seconds;
    if (held_ < hold_) return;
    trying_ = true;  // a new round, starting with the choice itself: its mean now
    held_ = 0.0;
    steps_ = 0;
    trial_seconds_ = 0.0;
    return;
  }
  if (warm_up_ > 0) {
    --warm_up_;
    return;
  }
  ++steps_;
  trial_seconds_ += seconds;
  if (steps_ >= kTrialSteps && trial_seconds_ >= kTrialSeconds) end_trial();
}

void ThreadTuner::end_trial() {
  mean_[current_] = trial_seconds_ / steps_;
  steps_ = 0;
  trial_seconds_ = 0.0;
  const std::size_t next = (current_ + 1) % sizes_.size();
  if (next == chosen_) {  // every size tried in this round, the choice first
    choose();
    return;
  }
  current_ = next;
  warm_up_ = kWarmUpSteps;
}

void ThreadTuner::choose() {
  const auto best =
      static_cast<std::size_t>(std::min_element(mean_.begin(), mean_.end()) - mean_.begin());
  // A confirmed choice is held twice as long next time; a new one from the first hold on.
  hold_ = best == chosen_ ? std::min(2.0 * hold_, kLongestHold) : kFirstHold;
  chosen_ = current_ = best;
  trying_ = false;
  held_ = 0.0;
}

std::string ThreadTuner::account() const {
  double total = 0.0;
  for (double s : seconds_on_) total += s;
  if (!(total > 0.0)) return "";
  std::ostringstream out;
  const char* separator = "";
  for (std::size_t i = 0; i < sizes_.size(); ++i) {
    if (seconds_on_[i] == 0.0) continue;
    out << separator << sizes_[i] << (sizes_[i] == 1 ? " thread " : " threads ")
        << static_cast<int>(100.0 * seconds_on_[i] / total + 0.5) << " %";
    separator = ", ";
  }
  return out.str() + " of the stepping time";
}

}  // namespace rumble::fem
