// A validated scenario as typed values, built once before a run: what the run needs and where
// each part came from (JSON pointers for messages). The JSON document itself is kept, as
// validated with its defaults filled, for summary.json.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "scenario/diagnostic.hpp"
#include "track_spec/track_config.hpp"

namespace rumble::scenario {

/// A plugin component: {type, params} at a JSON pointer.
struct ComponentSpec {
  std::string pointer;  // e.g. "/soil", "/coupling/participants/reduced_soil"
  std::string type;
  nlohmann::json params = nlohmann::json::object();
};

struct VehicleSpec {
  ComponentSpec component;
  std::string name;    // label in results
  double speed = 0.0;  // m/s
  double start = 0.0;  // m, position of the vehicle reference at t = 0
};

/// A receiver: a surface distance from the scenario (named "d=<y> m", at mid-track) or a named
/// point.
struct ReceiverSpec {
  std::string name;
  double x = 0.0, y = 0.0, depth = 0.0;  // m
};

struct OutputSpec {
  std::filesystem::path directory;  // resolved: relative to the scenario file
  std::vector<ReceiverSpec> receivers;
  double receiver_interval = 0.0;        // s, 0: every soil step
  std::optional<double> field_interval;  // s, soil field snapshots
  std::size_t every = 1;                 // record every n-th macro step
  bool plots = true;
};

/// /coupling/divergence: when a run counts as diverging and what it then does.
struct DivergenceSpec {
  double displacement_factor = 20.0;  // [-] of a soil's largest static footprint displacement
  bool stop = true;                   // false: warn once and go on
};

struct RunSpec {
  std::filesystem::path path;  // the scenario file
  nlohmann::json document;     // as validated, defaults filled
  double t_end = 0.0;          // s
  double macro_step = 0.0;     // s
  std::vector<VehicleSpec> vehicles;
  TrackConfig track;
  ComponentSpec soil, coupling;
  DivergenceSpec divergence;
  std::vector<std::pair<std::string, ComponentSpec>> participants;  // the coupler's extras
  OutputSpec outputs;
  /// Values set from outside the file (`rumble run --set`), [{"pointer", "value"}] in the order
  /// applied (already applied to `document`): summary.json's "overrides".
  nlohmann::json overrides = nlohmann::json::array();

  /// x [m] of the middle of the sleepers: where distance receivers stand.
  double track_middle() const;
};

/// /outputs/receivers as receivers, in order: a number is a surface distance at x_mid [m].
std::vector<ReceiverSpec> receivers(const nlohmann::json& list, double x_mid);

/// The name of a receiver given by its distance y [m] from the track axis: "d=2.5 m".
std::string distance_receiver_name(double y);

/// document: valid against the engine's and the plugins' schemas, defaults filled.
RunSpec make_run_spec(const nlohmann::json& document, const std::filesystem::path& path);

/// Results directory of a scenario: outputs.directory relative to the scenario file.
std::filesystem::path results_directory(const nlohmann::json& document,
                                        const std::filesystem::path& path);

/// What keeps the results that a file names inside that file's folder, for the messages.
struct ResultsFolderRule {
  std::string pointer;  // where the file names its results directory: "/outputs/directory"
  std::string file;     // what the file is: "scenario", "study file"
  std::string choices;  // how the command line allows another directory: "pass --allow-..."
};

/// Results go inside the folder of the file that names them unless the command line says
/// otherwise (issues #8, #30): the finding at rule.pointer when `given` (relative to the folder
/// of `file` unless absolute) is absolute, leaves that folder with "..", leads out of it through
/// a symbolic link (the part of the path that exists is resolved as the system resolves it), or
/// `file` is not a file in a folder (/dev/stdin, a pipe); nullopt when it stays inside.
std::optional<Diagnostic> outside_folder(const ResultsFolderRule& rule,
                                         const std::filesystem::path& file,
                                         const std::string& given);

/// outside_folder for a scenario's outputs.directory, which `rumble run` (and `mesh`,
/// `soil-frf`) allow with --output DIR or --allow-outside-results.
std::optional<Diagnostic> results_outside_scenario_folder(const nlohmann::json& document,
                                                          const std::filesystem::path& path);

}  // namespace rumble::scenario
