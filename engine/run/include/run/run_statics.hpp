#pragma once
// The static equilibrium a run starts from (docs/architecture.md, the run's steps): the track
// and its static partner soil solved together, the other soils started from the same footprint
// forces, and a soil integrated in the track checked against its own statics.

#include <filesystem>
#include <nlohmann/json.hpp>

#include "run/run_components.hpp"

namespace rumble {

/// A coupler declaring RUMBLE_CAP_MONOLITHIC: the scenario's soil, from its linear matrices, is
/// integrated inside the track (decision 0008). Returns whether it was.
bool integrate_soil_if_asked(RunComponents& c);

/// What the static equilibrium gave: its wall time, the wheel loads [N] and the track/soil
/// iterations.
struct StaticState {
  double seconds = 0.0;
  nlohmann::json wheel_loads = nlohmann::json::array();
  int iterations = 0;
};

/// The static equilibrium of c's track and soils, logged. A soil that honoured a stop request
/// inside its static solve makes it an Interrupted naming results_dir.
StaticState static_equilibrium(RunComponents& c, const std::filesystem::path& results_dir);

}  // namespace rumble
