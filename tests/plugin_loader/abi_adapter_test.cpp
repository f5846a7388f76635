// The wall between ABI versions (plugin/abi_adapter.hpp, docs/decisions/0011-abi-wall.md): tables
// shaped as ABI 1.0 (and 1.2) go in, the current calls come out, and what runs underneath is the
// plugin's own older function. Entries past a table's struct_size are never read: they hold
// functions that fail the test.
#include "plugin/abi_adapter.hpp"

#include <gtest/gtest.h>

#include <cstddef>
#include <string>
#include <vector>

namespace rumble {
namespace {

struct Seen {
  int mass_1_0 = 0, forces_1_0 = 0, kinematics_1_0 = 0, tangent_1_0 = 0, outputs_1_0 = 0;
  int newer = 0;  // calls of entries the table's struct_size does not cover
  double state[2] = {0.0, 0.0};
  rumble_step_report report{};
  rumble_group_residual residual{};
};
Seen seen;

/// A vehicle table as a 1.0 plugin built it: struct_size ends at `outputs`; the entries appended
/// since are filled here only to show that nothing reads them.
rumble_vehicle_api vehicle_1_0() {
  rumble_vehicle_api a{};
  a.struct_size = static_cast<std::uint32_t>(abi::table_size(RUMBLE_KIND_VEHICLE, 0));
  a.mass_matrix = [](rumble_instance*, const double* q, double* m) {
    ++seen.mass_1_0;
    m[0] = 2.0 * q[0];
    return RUMBLE_OK;
  };
  a.forces = [](rumble_instance*, double t, const double*, const double*, double* f) {
    ++seen.forces_1_0;
    f[0] = 10.0 * t;
    return RUMBLE_OK;
  };
  a.wheel_kinematics = [](rumble_instance*, const double* q, double* z, double* j) {
    ++seen.kinematics_1_0;
    z[0] = q[0];
    j[0] = 1.0;
    return RUMBLE_OK;
  };
  a.tangent = [](rumble_instance*, double, const double*, const double*, double*, double*) {
    ++seen.tangent_1_0;
    return RUMBLE_DISCARD;  // a 1.0 plugin's "not offered"
  };
  a.output_names = [](rumble_instance*) -> const char* { return "z [m];v [m/s]"; };
  a.outputs = [](rumble_instance*, double, const double* q, const double* qd, double* v) {
    ++seen.outputs_1_0;
    v[0] = q[0];
    v[1] = qd[0];
    return RUMBLE_OK;
  };
  a.mass_matrix2 = [](rumble_instance*, const double*, std::uint64_t, double*, std::uint64_t) {
    ++seen.newer;
    return RUMBLE_FATAL;
  };
  a.forces2 = [](rumble_instance*, double, const double*, const double*, std::uint64_t, double*) {
    ++seen.newer;
    return RUMBLE_FATAL;
  };
  return a;
}

/// A 1.0 factory: struct_size ends at `api`, no capabilities record.
rumble_factory factory_1_0(rumble_kind kind, const void* api) {
  rumble_factory f{};
  f.struct_size = static_cast<std::uint32_t>(offsetof(rumble_factory, api) + sizeof(f.api));
  f.kind = kind;
  f.type_name = "old";
  f.api = api;
  return f;
}

ComponentType type_of(const rumble_factory& f, std::uint32_t abi_minor) {
  ComponentType t;
  t.kind = static_cast<rumble_kind>(f.kind);
  t.type_name = f.type_name;
  t.unlisted_factory = &f;
  t.abi_minor = abi_minor;
  t.capabilities = abi::capabilities_of(t.kind, f);
  return t;
}

TEST(AbiAdapter, AVehicleOf10IsCalledWithLengthsAndRunsItsOwnCalls) {
  seen = {};
  const rumble_vehicle_api api = vehicle_1_0();
  const rumble_factory f = factory_1_0(RUMBLE_KIND_VEHICLE, &api);
  const ComponentType type = type_of(f, 0);
  EXPECT_FALSE(type.capabilities.declared);
  EXPECT_TRUE(type.capabilities.has(RUMBLE_CAP_TANGENT | RUMBLE_CAP_SAVE_RESTORE));
  const abi::VehicleCalls calls(type);

  double q = 1.5, qd = -0.5, m = 0.0, f_out = 0.0, z = 0.0, j = 0.0, k = 0.0, c = 0.0;
  EXPECT_EQ(calls.mass_matrix2(nullptr, &q, 1, &m, 1), RUMBLE_OK);
  EXPECT_EQ(m, 3.0);
  EXPECT_EQ(calls.forces2(nullptr, 0.25, &q, &qd, 1, &f_out), RUMBLE_OK);
  EXPECT_EQ(f_out, 2.5);
  EXPECT_EQ(calls.wheel_kinematics2(nullptr, &q, 1, &z, 1, &j), RUMBLE_OK);
  EXPECT_EQ(z, 1.5);
  ASSERT_TRUE(calls.offers_tangent());
  EXPECT_EQ(calls.tangent2(nullptr, 0.0, &q, &qd, 1, &k, &c), RUMBLE_DISCARD);
  std::vector<std::string> names;
  EXPECT_EQ(calls.output_names2(nullptr, names), RUMBLE_OK);
  EXPECT_EQ(names, (std::vector<std::string>{"z [m]", "v [m/s]"}));
  double values[2] = {0.0, 0.0};
  EXPECT_EQ(calls.outputs2(nullptr, 0.0, &q, &qd, 1, values, 2), RUMBLE_OK);
  EXPECT_EQ(values[1], -0.5);

  EXPECT_EQ(seen.mass_1_0, 1);
  EXPECT_EQ(seen.forces_1_0, 1);
  EXPECT_EQ(seen.kinematics_1_0, 1);
  EXPECT_EQ(seen.tangent_1_0, 1);
  EXPECT_EQ(seen.outputs_1_0, 1);
  EXPECT_EQ(seen.newer, 0) << "an entry past the 1.0 table's struct_size was called";
  EXPECT_EQ(abi::lifecycle_of(type), nullptr);
}

TEST(AbiAdapter, ASoilTableComesInTheCurrentShapeWithLaterEntriesNull) {
  rumble_lifecycle_api lifecycle{};
  rumble_soil_api plugin{};
  plugin.advance = [](rumble_instance*, double, double, const rumble_waveform*) {
    return RUMBLE_OK;
  };
  plugin.lifecycle = &lifecycle;  // past a 1.0 table's end: garbage to a 1.0 plugin
  plugin.set_probes = [](rumble_instance*, const rumble_probe*, std::uint64_t, double) {
    return RUMBLE_OK;
  };
  plugin.probe_resolution = [](rumble_instance*, double*, std::uint64_t, const char**) {
    return RUMBLE_OK;
  };

  plugin.struct_size = static_cast<std::uint32_t>(abi::table_size(RUMBLE_KIND_SOIL, 0));
  const rumble_factory f_1_0 = factory_1_0(RUMBLE_KIND_SOIL, &plugin);
  const rumble_soil_api old = abi::current_soil_table(type_of(f_1_0, 0));
  EXPECT_EQ(old.struct_size, sizeof(rumble_soil_api));
  EXPECT_EQ(old.advance, plugin.advance);
  EXPECT_EQ(old.lifecycle, nullptr);
  EXPECT_EQ(old.set_probes, nullptr);
  EXPECT_EQ(old.probe_resolution, nullptr);

  plugin.struct_size = static_cast<std::uint32_t>(abi::table_size(RUMBLE_KIND_SOIL, 2));
  const rumble_soil_api v1_2 = abi::current_soil_table(type_of(f_1_0, 2));
  EXPECT_EQ(v1_2.lifecycle, &lifecycle);
  EXPECT_EQ(v1_2.set_probes, plugin.set_probes);
  EXPECT_EQ(v1_2.probe_resolution, nullptr) << "1.3 appended it";
}

TEST(AbiAdapter, CheckpointsOfAPluginThatOnlySavesAreKeptByTheAdapter) {
  seen = {};
  rumble_common_api common{};
  common.state_size = [](rumble_instance*, std::uint64_t* n) {
    *n = 2;
    return RUMBLE_OK;
  };
  common.save_state = [](rumble_instance*, double* b, std::uint64_t n) {
    for (std::uint64_t i = 0; i < n; ++i) b[i] = seen.state[i];
    return RUMBLE_OK;
  };
  common.restore_state = [](rumble_instance*, const double* b, std::uint64_t n) {
    for (std::uint64_t i = 0; i < n; ++i) seen.state[i] = b[i];
    return RUMBLE_OK;
  };
  abi::Checkpoints slots(common, nullptr, Capabilities{RUMBLE_CAP_SAVE_RESTORE});
  ASSERT_FALSE(slots.plugin_held());
  seen.state[0] = 1.0;
  seen.state[1] = 2.0;
  EXPECT_EQ(slots.save(nullptr, 3), RUMBLE_OK);
  seen.state[0] = seen.state[1] = 9.0;
  EXPECT_TRUE(slots.restorable(3));
  EXPECT_FALSE(slots.restorable(0));
  for (int k = 0; k < 2; ++k) {  // a slot restores as often as asked
    EXPECT_EQ(slots.restore(nullptr, 3), RUMBLE_OK);
    EXPECT_EQ(seen.state[0], 1.0);
    EXPECT_EQ(seen.state[1], 2.0);
    seen.state[0] = 5.0;
  }
  EXPECT_EQ(slots.release(nullptr, 3), RUMBLE_OK);
  EXPECT_FALSE(slots.restorable(3));
}

rumble_status record_report(void*, const rumble_step_report* r) {
  seen.report = *r;
  seen.residual = r->residuals[0];
  return RUMBLE_OK;
}

TEST(AbiAdapter, A10CouplersStepDoneArrivesAsAStepReport) {
  seen = {};
  rumble_cosim_host host{};
  abi::fill_cosim_host_1_0<&record_report>(host);
  ASSERT_NE(host.step_done, nullptr);
  EXPECT_EQ(host.step_done(nullptr, 0.5, 1e-3, 0.02), RUMBLE_OK);
  EXPECT_EQ(abi::step_report_defect(&seen.report), "");
  EXPECT_EQ(seen.report.t, 0.5);
  EXPECT_EQ(seen.report.H, 1e-3);
  EXPECT_EQ(seen.report.iterations, 1u);
  EXPECT_EQ(seen.report.converged, 1);
  EXPECT_EQ(seen.report.participants, 0u);  // final for every participant
  ASSERT_EQ(seen.report.n_residuals, 1u);
  EXPECT_EQ(std::string(seen.residual.group), "interface");
  EXPECT_EQ(seen.residual.absolute, 0.02);
  EXPECT_EQ(seen.residual.relative, 0.02);
  EXPECT_FALSE(abi::coupler_takes_discard(0));
  EXPECT_TRUE(abi::coupler_takes_discard(1));
}

}  // namespace
}  // namespace rumble
