// How big a run will be, estimated from the scenario alone before anything runs or loads.
//
// Issue #8: valid scenarios exhausted the machine: time.macro_step 1e-12 s validated and then
// wrote about 1 GB a minute toward 5e10 steps; two_step reserved its force history up front and
// died of std::bad_alloc. Validation estimates the number of steps, the bytes the time histories
// will take on disk and the memory the run reserves for them, and refuses a run beyond the limits
// below unless the user confirms it (`rumble run --yes`, `rumble validate --yes`). The estimate
// covers what the engine and the in-tree couplers keep; a plugin's own memory (a FEM soil's mesh)
// is its own and not counted. Limits and formulas: docs/scenario.md, "Run size".
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "scenario/diagnostic.hpp"

namespace rumble::scenario {

inline constexpr double kMaxMacroSteps = 1e7;                  // e.g. 1000 s at 0.1 ms
inline constexpr double kMaxMicroSteps = 1e9;                  // track micro-steps over the run
inline constexpr double kMaxBytesWritten = 10.0 * (1u << 30);  // 10 GiB of CSV time histories
inline constexpr double kMaxMemoryBytes = 8.0 * (1u << 30);    // 8 GiB reserved for histories
inline constexpr double kMaxFieldSnapshots = 1e4;              // VTU snapshots (outputs.fields)

/// All counts as doubles: a scenario may ask for more than any integer type holds.
struct RunSize {
  double macro_steps = 0.0;      // ceil(time.end / time.macro_step)
  double micro_steps = 0.0;      // time.end / track.integrator.micro_step; 0 when not given
  double records = 0.0;          // rows of each time history: macro_steps / outputs.every + 1
  double values_per_record = 0;  // numbers in one row of the time histories but receivers.csv
  double receiver_rows = 0.0;    // rows of receivers.csv, at least (soils may sample faster)
  double bytes_written = 0.0;    // records x values_per_record x kBytesPerValue
  double memory_bytes = 0.0;     // what the run reserves for its histories up front
  double field_snapshots = 0.0;  // time.end / outputs.fields.interval + 1; 0 without fields
  double statics_bytes = 0.0;    // the track/soil statics' dense matrices: kStaticsBytesPerPair n^2
};

/// The track/soil statics (track/static_interface.cpp) hold about seven dense n x n matrices of
/// doubles for n footprints (the soil's flexibility shape, its prior and secant, the track's
/// Jacobian, the identity, the LU and a product): 56 n^2 bytes, 5.6 GB at 1e4 sleepers (the
/// 5.5 GB measured there), under kMaxMemoryBytes up to about 12 000 sleepers.
inline constexpr double kStaticsBytesPerPair = 56.0;

/// Bytes of one number in a CSV row: 9 significant digits, sign, exponent and separator.
inline constexpr double kBytesPerValue = 17.0;

/// scenario: valid against the engine's schema, defaults filled.
RunSize estimate_run_size(const nlohmann::json& scenario);

/// An error per limit the estimate exceeds, at the value to change, with the estimate and the
/// fix ("... or confirm it with --yes").
std::vector<Diagnostic> check_run_size(const nlohmann::json& scenario);

/// What this machine has free as a run starts (rumble/host_resources.hpp), in bytes.
struct MachineRoom {
  double memory_bytes = 0.0;  // available to new allocations (MemAvailable, the cgroup's limit)
  double disk_bytes = 0.0;    // free to the user on the results directory's file system
  std::string results;        // that directory, for the message
};

/// An error where the run's estimate exceeds what the machine has free now: the memory of the
/// statics and the histories (at /track/sleepers/count, /coupling/type or /time/end), the disk
/// the time histories take (at /outputs/every). Unlike the budgets of check_run_size, --yes does
/// not waive these: past them a run ends in std::bad_alloc, the OOM killer or a full disk.
std::vector<Diagnostic> check_machine_room(const nlohmann::json& scenario, const MachineRoom& room);

}  // namespace rumble::scenario
