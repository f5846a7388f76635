// A plugin built for ABI 1.0 keeps working under the 1.1 host. tests/boundary/abi_1_0_fixture.cpp
// is compiled twice, against the frozen 1.0 SDK (tests/abi/v1_0) and against the current one:
// the 1.0 build goes through the host's 1.0 paths (1.0 table sizes, calls without array
// lengths, step_done, DISCARD as ERROR) and the 1.1 build through the new ones, and every
// recorded number must be the same, to the byte.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>

#include "boundary_support.hpp"

namespace rumble::testing {
namespace {

const char* const kRecorded[] = {"contact.csv",
                                 "vehicles.csv",
                                 "footprint_force.csv",
                                 "footprint_displacement.csv",
                                 "footprint_velocity.csv",
                                 "interface.csv"};

nlohmann::json fixture_run(const std::string& suffix) {
  nlohmann::json s =
      fixture_scenario({{"type", "fixture_soil" + suffix}}, {{"type", "fixture_coupler" + suffix}});
  s["vehicles"][0]["type"] = "fixture_wheel" + suffix;
  s["vehicles"][0]["params"] = nlohmann::json::object();
  return s;
}

TEST(Abi10Plugin, IsListedWithItsAbiAndDerivedCapabilities) {
  ::setenv("RUMBLE_PLUGIN_PATH", fixture_plugin("abi_fixture_1_0").c_str(), 1);
  const CliResult r = run_rumble({"plugins", "--format", "json"});
  ::unsetenv("RUMBLE_PLUGIN_PATH");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const nlohmann::json listing = nlohmann::json::parse(r.output);
  bool found = false;
  for (const auto& lib : listing) {
    if (lib["plugin"] != "abi_fixture_1_0") continue;
    found = true;
    EXPECT_EQ(lib["abi"], "1.0");
    for (const auto& type : lib["types"]) {
      EXPECT_FALSE(type["capabilities"]["declared"].get<bool>()) << type;
      if (type["type"] == "fixture_soil_1_0") {
        // A 1.0 table built with the C++ SDK has every optional entry non-null; what is not
        // really offered answers DISCARD, which the host reads as "not offered" for 1.0 only.
        EXPECT_EQ(
            type["capabilities"]["offers"],
            nlohmann::json::array({"save_restore", "frequency_response", "surface_receivers"}));
      }
    }
  }
  EXPECT_TRUE(found) << r.output;
}

TEST(Abi10Plugin, RunsWithResultsIdenticalToTheSameSourceBuiltFor11) {
  CliResult old_run, new_run;
  const auto old_dir = run_in("abi_1_0_run", fixture_run("_1_0"), old_run);
  const auto new_dir = run_in("abi_1_1_run", fixture_run("_1_1"), new_run);
  ASSERT_EQ(old_run.exit_code, 0) << old_run.output;
  ASSERT_EQ(new_run.exit_code, 0) << new_run.output;
  EXPECT_EQ(read_json(old_dir / "summary.json")["status"], "completed");
  for (const char* file : kRecorded)
    EXPECT_TRUE(same_bytes(old_dir / file, new_dir / file)) << file << " differs";

  // And the 1.0 soil really ran: its static displacement is F / k (k = 1e8 N/m by default), to
  // the 9 significant digits the CSV files hold, and to the static consistency the engine
  // iterates to (1e-9 of the largest footprint displacement, track/static_interface.hpp, iterated
  // in track_statics.cpp).
  std::vector<double> t_f, force, t_u, u;
  read_csv(old_dir / "footprint_force.csv", t_f, force);
  read_csv(old_dir / "footprint_displacement.csv", t_u, u);
  ASSERT_GE(u.size(), 20u);
  double peak = 0.0, u_max = 0.0;
  for (std::size_t i = 0; i < 20; ++i) u_max = std::max(u_max, std::abs(u[i]));
  for (std::size_t i = 0; i < 20; ++i) {  // the first row: t = 0, 20 footprints
    EXPECT_NEAR(u[i], force[i] / 1.0e8, 1e-8 * (std::abs(force[i] / 1.0e8) + u_max)) << i;
    peak = std::max(peak, force[i]);
  }
  EXPECT_GT(peak, 1e3);  // the wheel's weight reached the soil
}

TEST(Abi10Plugin, CouplerDrivesTheHostLikeTheInTreeGaussSeidel) {
  // The 1.0 coupler knows the soil's outputs are u then v; gauss_seidel (1.1) matches channel
  // groups by name. Same algorithm (order 0, track first): same numbers.
  CliResult old_run, new_run;
  nlohmann::json in_tree = fixture_run("_1_0");
  in_tree["coupling"] = {{"type", "gauss_seidel"}};
  const auto old_dir = run_in("abi_1_0_coupler", fixture_run("_1_0"), old_run);
  const auto new_dir = run_in("abi_1_0_vs_gauss_seidel", in_tree, new_run);
  ASSERT_EQ(old_run.exit_code, 0) << old_run.output;
  ASSERT_EQ(new_run.exit_code, 0) << new_run.output;
  for (const char* file : {"contact.csv", "footprint_force.csv", "footprint_displacement.csv"})
    EXPECT_TRUE(same_bytes(old_dir / file, new_dir / file)) << file << " differs";
}

}  // namespace
}  // namespace rumble::testing
