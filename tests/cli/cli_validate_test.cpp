// `rumble validate` on the track and vehicle mistakes issue #3 names: each gives its pointer,
// the value and the rule, exit code 1 (or 0 with a warning for the critical-speed regime).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "cli_runner.hpp"

namespace rumble::testing {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

CliResult validate(const std::string& name, const nlohmann::json& scenario) {
  return run_rumble({"validate", write_scenario(scratch_directory(name), scenario).string()});
}

// Receiver and vehicle names become CSV column names (issue #30): a comma or quote would break
// the header and a second receiver of one name would take the first one's columns, so names are
// refused outside a documented character set, and each must be unique (the automatic "d=2.5 m"
// of a distance receiver included).
TEST(CliValidate, NamesAreUniqueAndFitACsvHeader) {
  const auto dir = scratch_directory("validate_names");
  nlohmann::json s = small_scenario();
  s["outputs"]["receivers"] = {{{"name", "a,b"}, {"y", 2.0}}};
  const CliResult comma = run_rumble({"validate", write_scenario(dir, s).string()});
  EXPECT_EQ(comma.exit_code, 1) << comma.output;
  EXPECT_THAT(comma.output, HasSubstr("/outputs/receivers/0/name: must match the pattern"));
  EXPECT_THAT(comma.output, HasSubstr("got \"a,b\""));
  EXPECT_THAT(comma.output, HasSubstr("hint: column name in receivers.csv, unique among the "
                                      "receivers: a letter or digit, then letters, digits, "
                                      "spaces and _ . = + ( ) - (no comma, quote or bracket"));
  s["outputs"]["receivers"] = {2.5, {{"name", "d=2.5 m"}, {"y", 3.0}}};
  s["vehicles"].push_back(s["vehicles"][0]);
  s["vehicles"][0]["name"] = "vehicle1";
  const CliResult twice = run_rumble({"validate", write_scenario(dir, s).string()});
  EXPECT_EQ(twice.exit_code, 1) << twice.output;
  EXPECT_THAT(twice.output, HasSubstr("error: /outputs/receivers/1: receiver name \"d=2.5 m\" is "
                                      "taken by /outputs/receivers/0\n    hint: give each "
                                      "receiver its own name"));
  EXPECT_THAT(twice.output, HasSubstr("error: /vehicles/1: vehicle name \"vehicle1\" is taken by "
                                      "/vehicles/0\n    hint: give each vehicle its own name"));
}

TEST(CliValidate, NegativeMass) {
  nlohmann::json s = small_scenario();
  s["vehicles"][0]["params"]["mass"] = -750.0;
  const CliResult r = validate("negative_mass", s);
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_THAT(r.output,
              HasSubstr("error: /vehicles/0/params/mass: must be in [1, 1e+05], got -750"));
}

TEST(CliValidate, ZeroSleeperSpacing) {
  nlohmann::json s = small_scenario();
  s["track"]["sleepers"]["spacing"] = 0;
  const CliResult r = validate("zero_spacing", s);
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_THAT(r.output, HasSubstr("error: /track/sleepers/spacing: must be in [0.1, 2], got 0"));
}

TEST(CliValidate, UnknownUnevennessClass) {
  nlohmann::json s = small_scenario();
  s["track"]["unevenness"] = {{"type", "random"},
                              {"class", "FRA7"},
                              {"seed", 1},
                              {"wavelength_min", 1.0},
                              {"wavelength_max", 30.0}};
  const CliResult r = validate("unevenness_class", s);
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_THAT(r.output, HasSubstr("/track/unevenness/class: must be one of: FRA1, FRA2, FRA3, "
                                  "FRA4, FRA5, FRA6, ISO3095, got \"FRA7\""));
}

TEST(CliValidate, WavelengthBandMustBeOrdered) {
  nlohmann::json s = small_scenario();
  s["track"]["unevenness"] = {{"type", "random"},
                              {"class", "FRA4"},
                              {"seed", 1},
                              {"wavelength_min", 30.0},
                              {"wavelength_max", 1.0}};
  const CliResult r = validate("wavelength_band", s);
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_THAT(r.output, HasSubstr("/track/unevenness/wavelength_max: must be > wavelength_min = "
                                  "30 m, got 1 m"));
}

// ISO 3095 is a rail roughness spectrum (3 mm to 0.45 m): a track-geometry band is refused by
// validate (exit 1), not left to fail the run (exit 3).
TEST(CliValidate, Iso3095BandOutsideItsRange) {
  nlohmann::json s = small_scenario();
  s["track"]["unevenness"] = {{"type", "random"},
                              {"class", "ISO3095"},
                              {"seed", 1},
                              {"wavelength_min", 1.0},
                              {"wavelength_max", 30.0}};
  const CliResult r = validate("iso3095_band", s);
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_THAT(r.output,
              HasSubstr("error: /track/unevenness/wavelength_max: the ISO3095 spectrum "
                        "is defined for wavelengths from 0.00281838 m to 0.446684 m, got 30 m"));
  EXPECT_THAT(r.output, HasSubstr("for track geometry (1 to 30 m) use an FRA class"));
  EXPECT_THAT(r.output, Not(HasSubstr("wavelength_min")));  // 1 m is inside the range
}

// Soft soil: c_R = 42.9 m/s (docs/physics.md §2); 50 m/s is above it: a warning with the number,
// not an error (the run is allowed).
TEST(CliValidate, SpeedAboveRayleighSpeedWarns) {
  nlohmann::json s = small_scenario();
  s["soil"] = {{"type", "winkler"}, {"params", {{"E", 1e7}, {"nu", 0.3}, {"rho", 1800.0}}}};
  s["vehicles"][0]["speed"] = 50.0;
  s["time"]["end"] = 0.1;
  const CliResult r = validate("rayleigh", s);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("warning: /vehicles/0/speed: the speed 50 m/s is above the "
                                  "soil's Rayleigh wave speed 42.9 m/s (critical-speed regime)"));
}

// A layered soil: the warning takes the slowest layer, not the half-space (the soil reports it;
// the engine does not read its params). 2 m of 10 MPa over 750 MPa: c_R = 42.9 m/s on top.
TEST(CliValidate, SpeedAboveTheTopLayersRayleighSpeedWarns) {
  nlohmann::json s = small_scenario();
  s["soil"] = {{"type", "clm"},
               {"params",
                {{"E", 7.5e8},
                 {"nu", 0.3},
                 {"rho", 1800.0},
                 {"layers", {{{"thickness", 2.0}, {"E", 1e7}, {"nu", 0.3}, {"rho", 1800.0}}}}}}};
  s["vehicles"][0]["speed"] = 50.0;
  s["time"]["end"] = 0.1;
  const CliResult r = validate("rayleigh_layered", s);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("warning: /vehicles/0/speed: the speed 50 m/s is above the "
                                  "soil's Rayleigh wave speed 42.9 m/s (critical-speed regime)"));
}

// What only the plugin knows is found by validate too (it builds the components as a run does):
// a constructor refusing its params, and a soil refusing the track's footprint layout.
TEST(CliValidate, ASoilRefusingItsParamsIsAValidateError) {
  nlohmann::json s = small_scenario();
  s["soil"] = {{"type", "clm"},
               {"params", {{"m_f", 0.0}, {"k_f", 1e8}, {"c_f", 0.0}, {"k_c", 1e8}, {"c_c", 1e5}}}};
  const CliResult r = validate("soil_refuses_params", s);
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_THAT(r.output, HasSubstr("error: /soil/params: /soil: soil type 'clm' refused its params: "
                                  "clm: with m_f = 0 and c_c > 0 the ground dashpot c_f must be "
                                  "> 0, got 0"));
}

TEST(CliValidate, ASoilRefusingTheLayoutIsAValidateError) {
  nlohmann::json s = small_scenario();
  s["soil"] = {{"type", "clm"}, {"params", {{"E", 1.55e8}, {"nu", 0.3}, {"rho", 1800.0}}}};
  s["track"]["sleepers"]["spacing"] = 0.2;  // narrower than the 0.26 m sleepers
  s["vehicles"][0]["start"] = 1.0;
  s["time"]["end"] = 0.01;
  const CliResult r = validate("soil_refuses_layout", s);
  EXPECT_EQ(r.exit_code, 1) << r.output;
  // Blamed on the track, whose sleepers the layout is (issue #30 item 5: it said /soil).
  EXPECT_THAT(r.output, HasSubstr("error: /track/sleepers: soil 'clm' (/soil): accept_layout "
                                  "failed: clm: footprints overlap"));
}

// A plugin that names the key it refuses ("fem: params/mesh/radius: ...") is blamed there, not
// on its params as a whole (issue #30 item 5): here the footprints of 40 sleepers do not fit
// the 6 m hemisphere, found when the FEM soil takes the layout.
TEST(CliValidate, ASoilsRefusalPointsAtTheKeyItNames) {
  nlohmann::json s = small_fem_scenario();
  s["track"]["sleepers"]["count"] = 40;
  const CliResult r = validate("soil_names_its_key", s);
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_THAT(r.output, HasSubstr("error: /soil/params/mesh/radius: soil 'fem' (/soil): "
                                  "accept_layout failed: fem: params/mesh/radius: the footprints "
                                  "span "));
  EXPECT_THAT(r.output, HasSubstr("give a radius of at least"));
}

// A FEM soil's receiver outside its mesh failed the run at its first call, blamed on the soil
// ("soil 'fem' (/soil): set_probes failed"), and validate said the scenario was valid (issue #30
// item 5). Validation now asks the soil it builds, and names the receiver, its pointer and
// where it stands.
TEST(CliValidate, AReceiverOutsideTheSoilsMeshIsBlamedAtItsPointer) {
  nlohmann::json s = small_fem_scenario();
  s["outputs"]["receivers"] = {2.0, 100.0};
  const CliResult r = validate("receiver_outside_mesh", s);
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_THAT(r.output, HasSubstr("error: /outputs/receivers/1: receiver 'd=100 m' (x "));
  EXPECT_THAT(r.output, HasSubstr("y 100 m, depth 0 m) cannot be recorded by soil 'fem' (/soil): "
                                  "set_probes failed: fem: receiver 'd=100 m'"));
  EXPECT_THAT(r.output, HasSubstr("lies outside the mesh"));
  EXPECT_THAT(r.output, HasSubstr("hint: move the receiver into the soil's domain"));
  EXPECT_THAT(r.output, ::testing::Not(HasSubstr("/outputs/receivers/0")));
}

}  // namespace
}  // namespace rumble::testing
