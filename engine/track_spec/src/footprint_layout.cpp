#include "track_spec/footprint_layout.hpp"

namespace rumble {

std::vector<rumble_footprint> footprint_layout(const TrackConfig& c) {
  std::vector<rumble_footprint> fp(static_cast<std::size_t>(c.sleeper_count));
  for (std::size_t i = 0; i < fp.size(); ++i)
    fp[i] = {c.sleeper_x(static_cast<int>(i)), 0.0, c.footprint_length, c.footprint_width};
  return fp;
}

}  // namespace rumble
