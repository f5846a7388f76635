// The footprints the track announces to the soil: one whole-sleeper print per sleeper, centred
// on the track axis at x = i * spacing.
#pragma once

#include <rumble/abi.h>

#include <vector>

#include "track_spec/track_config.hpp"

namespace rumble {

std::vector<rumble_footprint> footprint_layout(const TrackConfig& config);

}  // namespace rumble
