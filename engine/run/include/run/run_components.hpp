// The components of a run, built from its typed scenario: the vehicles on the track, the soil
// and the coupler's extra soils on the track's footprints, the coupler, and the receivers handed
// to the soil (ABI 1.1 probes, or the 1.0 surface receivers of an older soil).
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "plugin/built_soils.hpp"
#include "plugin/instance.hpp"
#include "scenario/run_spec.hpp"
#include "track/integrated_soil.hpp"
#include "track/track_participant.hpp"

namespace rumble {

/// How the soil records the scenario's receivers.
struct ReceiverSetup {
  bool probes = false;            // ABI 1.1: every receiver, 3 components, inside steps
  bool surface = false;           // ABI 1.0: vertical velocity at macro-step ends
  std::vector<double> distances;  // m, the 1.0 receivers (surface points at mid-track only)
};

struct RunComponents {
  std::unique_ptr<TrackParticipant> track;
  std::unique_ptr<SoilInstance> soil;
  std::vector<std::pair<std::string, std::unique_ptr<SoilInstance>>> extras;  // by name
  std::unique_ptr<CouplerInstance> coupler;
  ReceiverSetup receivers;

  /// Every plugin instance: the soil, the extra soils, the coupler, then the vehicles.
  std::vector<Instance*> instances() const;
};

/// Throws ConfigError for a type no plugin provides (validation has normally caught it) or a
/// component refusing its params or the layout. A soil that validation built from the same type,
/// params and layout is taken from `built` instead of being built again.
RunComponents build_components(const scenario::RunSpec& spec, const PluginRegistry& registry,
                               BuiltSoils* built = nullptr);

/// What rumble_host tells the plugins during the run: the results directory, and the threads
/// each may use: all cores for the soils, one for the rest. The time stepping may take one from
/// the soil while the track advances beside it (run/core_share.hpp).
void give_run_context(RunComponents& c, const std::filesystem::path& results_dir);

/// The soil as its linear matrices (M, C, K, B) describe it, for `purpose` ("a monolithic
/// coupler", "a stability analysis"); throws ConfigError naming the fix when it gives none.
std::unique_ptr<IntegratedSoil> linear_soil(SoilInstance& soil, const std::string& purpose);

/// Lets every plugin flush after a run that completed or stopped cleanly (lifecycle finalize).
void finalize_components(RunComponents& c);

}  // namespace rumble
