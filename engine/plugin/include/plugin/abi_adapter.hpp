// The wall between ABI versions (docs/decisions/0011-abi-wall.md). A plugin may be built for any
// ABI 1.x up to this engine's; here, at the loader, whatever table it gives is read in the
// current shape, and the engine past this file knows only that shape: every call with its array
// lengths (the `*2` forms ABI 1.1 appended), one step report, one checkpoint path. Every
// translation of an older minor lives in abi_adapter.cpp; what each minor's table must hold is
// checked when the library loads (function_table.hpp).
#pragma once

#include <rumble/abi.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "plugin/registry.hpp"

namespace rumble::abi {

/// Bytes of a kind's table that a plugin built for ABI 1.`abi_minor` holds at least: the end of
/// the last entry that minor has.
std::size_t table_size(rumble_kind kind, std::uint32_t abi_minor);

/// A factory's capabilities: as declared (ABI 1.1 on) or, for a 1.0 factory, derived from which
/// of its optional functions are non-null (save/restore assumed: the 1.0 table always has it;
/// state_size says at run time).
Capabilities capabilities_of(rumble_kind kind, const rumble_factory& f);

/// A component's lifecycle table (ABI 1.1); null for a 1.0 plugin, or when none is offered.
const rumble_lifecycle_api* lifecycle_of(const ComponentType& type);

/// A soil's table in the current shape: the entries of the plugin's minor, those appended since
/// null (a 1.0 soil has no lifecycle and no probes, a 1.2 soil no probe_resolution).
rumble_soil_api current_soil_table(const ComponentType& type);

/// A coupler's table in the current shape (a 1.0 coupler: no lifecycle).
rumble_coupler_api current_coupler_table(const ComponentType& type);

/// A vehicle's calls in the current shape, every array with its length: a 1.0 vehicle's calls
/// without lengths are made underneath.
class VehicleCalls {
 public:
  explicit VehicleCalls(const ComponentType& type);
  /// The same for a table given directly (ABI 1.`abi_minor`, its capabilities).
  VehicleCalls(const rumble_vehicle_api& api, std::uint32_t abi_minor, const Capabilities& caps);
  rumble_status dof_count(rumble_instance* self, std::uint64_t* n_dof) const;
  rumble_status wheels(rumble_instance* self, rumble_wheel* out, std::uint64_t capacity,
                       std::uint64_t* n_wheels) const;
  rumble_status mass_matrix2(rumble_instance* self, const double* q, std::uint64_t n_dof,
                             double* mass, std::uint64_t n_mass) const;
  rumble_status forces2(rumble_instance* self, double t, const double* q, const double* qd,
                        std::uint64_t n_dof, double* f) const;
  rumble_status wheel_kinematics2(rumble_instance* self, const double* q, std::uint64_t n_dof,
                                  double* z, std::uint64_t n_wheels, double* jacobian) const;
  /// Whether tangent2 may be called: declared (1.1 on), or present in a 1.0 table, whose
  /// DISCARD from it still means "not offered" (the caller reads it so).
  bool offers_tangent() const { return tangent_; }
  rumble_status tangent2(rumble_instance* self, double t, const double* q, const double* qd,
                         std::uint64_t n_dof, double* stiffness, double* damping) const;
  /// The output channel names (none when the vehicle has no outputs).
  rumble_status output_names2(rumble_instance* self, std::vector<std::string>& names) const;
  rumble_status outputs2(rumble_instance* self, double t, const double* q, const double* qd,
                         std::uint64_t n_dof, double* values, std::uint64_t n_values) const;

 private:
  const rumble_vehicle_api* api_;
  bool lengths_;  // the table has the 1.1 calls with lengths (the loader checked them)
  bool tangent_;
};

/// One instance's checkpoint slots (0 .. RUMBLE_CHECKPOINT_SLOTS - 1) through one path. A plugin
/// that declares own checkpoints keeps them itself (lifecycle checkpoint_*: a large state is
/// never copied); for one that only saves and restores its state (every 1.0 plugin) the slots
/// are kept here, filled by the common save_state and read back by restore_state.
class Checkpoints {
 public:
  Checkpoints(const rumble_common_api& common, const rumble_lifecycle_api* lifecycle,
              const Capabilities& capabilities);
  bool plugin_held() const { return plugin_held_; }
  /// Doubles a slot kept here holds (0: the plugin cannot save); not asked when plugin-held.
  rumble_status state_size(rumble_instance* self, std::uint64_t* n) const;
  /// False for a slot kept here that was never saved (or was freed since).
  bool restorable(std::uint32_t slot) const { return plugin_held_ || saved_.at(slot); }
  rumble_status save(rumble_instance* self, std::uint32_t slot);
  rumble_status restore(rumble_instance* self, std::uint32_t slot) const;
  rumble_status release(rumble_instance* self, std::uint32_t slot);

 private:
  const rumble_common_api* common_;
  const rumble_lifecycle_api* lifecycle_;
  bool plugin_held_;
  std::array<std::vector<double>, RUMBLE_CHECKPOINT_SLOTS> slots_;  // allocated once per slot
  std::array<bool, RUMBLE_CHECKPOINT_SLOTS> saved_{};
};

/// Whether a coupler built for ABI 1.`abi_minor` is told DISCARD when a participant refuses a
/// step (1.1 on); a 1.0 coupler, which cannot retry, gets ERROR as it always did.
bool coupler_takes_discard(std::uint32_t abi_minor);

/// "" when a coupler's step report holds every field of ABI 1.1's record, else what is wrong.
std::string step_report_defect(const rumble_step_report* report);

/// The one entry of the participant interface only a 1.0 coupler calls, expressed through the
/// current one: its report of a final step with one residual is the step report of one group,
/// "interface", final for every participant. Report: the host's step_report.
template <rumble_status (*Report)(void*, const rumble_step_report*)>
void fill_cosim_host_1_0(rumble_cosim_host& table) {
  table.step_done = [](void* ctx, double t, double H, double residual) {
    const rumble_group_residual group{"interface", residual, residual};
    rumble_step_report report{};
    report.struct_size = sizeof(rumble_step_report);
    report.iterations = 1;
    report.t = t;
    report.H = H;
    report.converged = 1;
    report.n_residuals = 1;
    report.residuals = &group;
    report.participants = 0;
    return Report(ctx, &report);
  };
}

}  // namespace rumble::abi
