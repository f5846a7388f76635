#include "run/core_share.hpp"

#include <algorithm>
#include <cmath>

namespace rumble {

CoreShare::CoreShare(unsigned cores, bool two_at_once)
    : cores_(std::max(1u, cores)),
      grant_(two_at_once ? std::max(1u, cores_ - 1) : cores_),
      deciding_(grant_ < cores_) {}

unsigned CoreShare::after_step(double track_seconds, double soil_seconds, bool overlapped) {
  if (!deciding_) return 0;
  ++steps_;
  if (steps_ <= kSkipSteps) {
    track_from_ = track_seconds;
    soil_from_ = soil_seconds;
    return 0;
  }
  overlapped_ = overlapped_ || overlapped;
  if (steps_ < kSkipSteps + kWindowSteps) return 0;
  deciding_ = false;
  const double track = track_seconds - track_from_, soil = soil_seconds - soil_from_;
  if (!overlapped_) {
    reason_ = "the coupler advanced the track and the soil one after the other";
  } else if (track < soil / (2.0 * cores_)) {
    reason_ = "the track's advance took " +
              std::to_string(static_cast<int>(std::lround(100.0 * track / soil))) +
              " % of the soil's";
  } else {
    return 0;  // alike enough for the track's core to pay
  }
  grant_ = cores_;
  return grant_;
}

}  // namespace rumble
