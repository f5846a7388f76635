// Builds vehicle/track participants for tests from JSON snippets, with the in-tree vehicle
// plugins loaded from the build tree (RUMBLE_TEST_PLUGIN_DIR).
#pragma once

#include <memory>
#include <nlohmann/json.hpp>

#include "plugin/registry.hpp"
#include "track/track_participant.hpp"

namespace rumble::testing {

/// The REF-A track of docs/physics.md §1.1 and §8 (UIC60 on pads and half-sleepers on ballast,
/// railFE values per rail), `sleepers` sleepers at 0.6 m.
nlohmann::json ref_a_track(int sleepers, int elements_per_bay = 4);

/// Registry with the in-tree plugins (loaded once per process).
const PluginRegistry& plugins();

/// A track with one vehicle per entry of `vehicles` ({type, params, speed, start}).
std::unique_ptr<TrackParticipant> make_track(const nlohmann::json& track,
                                             const nlohmann::json& vehicles);

/// A single_wheel vehicle entry: total static wheel load `load` [N] (own weight included).
nlohmann::json single_wheel(double mass, double load, double speed, double start);

}  // namespace rumble::testing
