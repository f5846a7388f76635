// Hostile values (issue #30 item 3): every number has a physical range in its schema, so a value
// far outside it is refused by `rumble validate` at once (exit 1), naming the JSON pointer, the
// value and the allowed range, with the reason as the hint, instead of hanging the engine (a FEM
// soil's E = 1e300 hung an eigen-solver), crashing it (a mesh.radius of 1e9) or running it out
// of memory (a tiny mesh.h_near or boundary.pml.thickness). docs/scenario.md, "Limits".
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <chrono>
#include <ostream>
#include <string>
#include <vector>

#include "cli_runner.hpp"

// A named namespace: the CLI tests share a unity build.
namespace rumble::testing::hostile_values {

using ::testing::HasSubstr;

enum class Base { kSmall, kFem };

struct HostileCase {
  const char* name;     // the gtest name
  Base base;            // small_scenario() (winkler) or small_fem_scenario()
  const char* pointer;  // set by --set
  const char* value;    // JSON, as given to --set
  const char* error;    // the golden substring: "<pointer>: must be in <range>, got <value>"
  const char* reason;   // a piece of the hint (the description's reason for the range)
};

// Wall-clock limit of one validation [s]: each takes well under a second; a value that reached
// the solvers would take minutes or never end.
constexpr double kSecondsAtMost = 10.0;

const std::vector<HostileCase>& hostile_cases() {
  static const std::vector<HostileCase> cases = {
      // The soil's material (plugins/soils/common/soil_params.hpp), on the FEM soil whose
      // eigen-solver E = 1e300 hung.
      {"FemYoungsModulusHuge", Base::kFem, "/soil/params/E", "1e300",
       "/soil/params/E: must be in [1e+05, 1e+12], got 1e+300", "from peat"},
      {"FemYoungsModulusTiny", Base::kFem, "/soil/params/E", "1e-300",
       "/soil/params/E: must be in [1e+05, 1e+12], got 1e-300", "to hard rock"},
      {"FemPoissonRatioIncompressible", Base::kFem, "/soil/params/nu", "0.49999999",
       "/soil/params/nu: must be in [0, 0.495], got 0.49999999", "water-saturated clay"},
      {"FemDensityHuge", Base::kFem, "/soil/params/rho", "1e30",
       "/soil/params/rho: must be in [500, 5000], got 1e+30", "dense rock"},
      {"FemLayerThicknessTiny", Base::kFem, "/soil/params/layers",
       R"([{"thickness": 1e-9, "E": 3e8, "nu": 0.3, "rho": 1700}])",
       "/soil/params/layers/0/thickness: must be in [0.05, 1000], got 1e-09", "asphalt"},
      // The FEM soil's mesh and boundary (plugins/soils/fem/fem_settings.cpp).
      {"FemMeshRadiusHuge", Base::kFem, "/soil/params/mesh/radius", "1e9",
       "/soil/params/mesh/radius: must be in [1, 1000], got 1e+09", "within some 100 m"},
      {"FemMeshHNearTiny", Base::kFem, "/soil/params/mesh/h_near", "1e-9",
       "/soil/params/mesh/h_near: must be in [0.01, 100], got 1e-09", "footprint is 0.26 m"},
      {"FemMeshHMaxTiny", Base::kFem, "/soil/params/mesh/h_max", "1e-9",
       "/soil/params/mesh/h_max: must be in [0.01, 1000], got 1e-09", "h_near's smallest"},
      {"FemMeshFMaxTiny", Base::kFem, "/soil/params/mesh/f_max", "1e-300",
       "/soil/params/mesh/f_max: must be in [1, 2000], got 1e-300", "ground-borne noise"},
      {"FemMeshMaxDofsHuge", Base::kFem, "/soil/params/mesh/max_dofs", "1e300",
       "/soil/params/mesh/max_dofs: must be in [1000, 1e+09], got 1e+300", "a terabyte"},
      {"FemPmlThicknessTiny", Base::kFem, "/soil/params/boundary",
       R"({"type": "pml", "pml": {"thickness": 1e-9}})",
       "/soil/params/boundary/pml/thickness: must be in [0.5, 1000], got 1e-09",
       "absorbs waves as long as"},
      {"FemDampingRatioHuge", Base::kFem, "/soil/params/damping/ratio", "1e3",
       "/soil/params/damping/ratio: must be in [0, 0.5], got 1000", "soils are 0.01 to 0.1"},
      {"FemDampingFrequencyHuge", Base::kFem, "/soil/params/damping/f_high", "1e300",
       "/soil/params/damping/f_high: must be in [0.1, 10000], got 1e+300", "band of interest"},
      {"FemBoundarySpringFactorHuge", Base::kFem, "/soil/params/boundary/alpha_normal", "1e300",
       "/soil/params/boundary/alpha_normal: must be in [0, 10], got 1e+300", "Liu et al."},
      {"FemImplicitStepTiny", Base::kFem, "/soil/params/integrator",
       R"({"scheme": "implicit", "max_step": 1e-300})",
       "/soil/params/integrator/max_step: must be in [1e-07, 1], got 1e-300", "20 steps per"},
      // The reduced soil (winkler) of small_scenario().
      {"WinklerStiffnessHuge", Base::kSmall, "/soil/params/k", "1e300",
       "/soil/params/k: must be in [10000, 1e+13], got 1e+300", "Gazetas"},
      {"WinklerSubStepTiny", Base::kSmall, "/soil/params/max_step", "1e-300",
       "/soil/params/max_step: must be in [1e-07, 1], got 1e-300", "far finer"},
      // The scenario (engine/scenario/src/scenario_schema.cpp).
      {"MacroStepTiny", Base::kSmall, "/time/macro_step", "1e-300",
       "/time/macro_step: must be in [1e-07, 1], got 1e-300", "micro-step"},
      {"EndHuge", Base::kSmall, "/time/end", "1e300",
       "/time/end: must be in [1e-06, 3600], got 1e+300", "an hour"},
      {"SpeedHuge", Base::kSmall, "/vehicles/0/speed", "1e9",
       "/vehicles/0/speed: must be in [0, 200], got 1e+09", "speed record"},
      {"StartHuge", Base::kSmall, "/vehicles/0/start", "-1e300",
       "/vehicles/0/start: must be in [-1e+06, 1e+06], got -1e+300", "beyond any track"},
      {"SleeperCountBeyondItsMaximum", Base::kSmall, "/track/sleepers/count", "100001",
       "/track/sleepers/count: must be in [3, 100000], got 100001", "60 km"},
      {"SleeperSpacingTiny", Base::kSmall, "/track/sleepers/spacing", "1e-300",
       "/track/sleepers/spacing: must be in [0.1, 2], got 1e-300", "0.5 to 0.75 m"},
      {"SleeperMassTiny", Base::kSmall, "/track/sleepers/mass", "1e-300",
       "/track/sleepers/mass: must be in [1, 5000], got 1e-300", "timber sleeper"},
      {"RailModulusHuge", Base::kSmall, "/track/rail/E", "1e300",
       "/track/rail/E: must be in [1e+09, 1e+12], got 1e+300", "2.1e11"},
      {"RailpadStiffnessHuge", Base::kSmall, "/track/railpad/k", "1e30",
       "/track/railpad/k: must be in [1e+05, 1e+11], got 1e+30", "railpads"},
      {"BallastDampingHuge", Base::kSmall, "/track/ballast/c", "1e30",
       "/track/ballast/c: must be in [0, 1e+07], got 1e+30", "ballast"},
      {"HertzConstantHuge", Base::kSmall, "/track/contact/hertz_constant", "1e300",
       "/track/contact/hertz_constant: must be in [1e+09, 1e+13], got 1e+300", "steel wheels"},
      {"MicroStepTiny", Base::kSmall, "/track/integrator/micro_step", "1e-300",
       "/track/integrator/micro_step: must be in [1e-09, 1], got 1e-300", "contact needs"},
      {"DipDepthHuge", Base::kSmall, "/track/unevenness",
       R"({"type": "dip", "position": 6, "length": 0.3, "depth": 1e3})",
       "/track/unevenness/depth: must be in [1e-07, 0.1], got 1000", "no wheel rides"},
      {"ReceiverDistanceHuge", Base::kSmall, "/outputs/receivers", "[1e12]",
       "/outputs/receivers/0: must be in (0, 1000], got 1e+12", "within some 100 m"},
      {"ReceiverDepthHuge", Base::kSmall, "/outputs/receivers",
       R"([{"name": "deep", "y": 2, "depth": 1e12}])",
       "/outputs/receivers/0/depth: must be in [0, 1000], got 1e+12", "reaches some 10 m"},
      {"ReceiverIntervalHuge", Base::kSmall, "/outputs/receiver_interval", "1e300",
       "/outputs/receiver_interval: must be in [0, 1], got 1e+300", "records none"},
      {"FieldIntervalTiny", Base::kSmall, "/outputs/fields", R"({"interval": 1e-300})",
       "/outputs/fields/interval: must be in [1e-06, 3600], got 1e-300", "finer than any"},
      {"RecordEveryHuge", Base::kSmall, "/outputs/every", "1000000000000",
       "/outputs/every: must be in [1, 10000000], got 1000000000000", "at most 1e7"},
      // The vehicle (plugins/vehicles/single_wheel).
      {"WheelMassTiny", Base::kSmall, "/vehicles/0/params/mass", "1e-300",
       "/vehicles/0/params/mass: must be in [1, 1e+05], got 1e-300", "half a wheelset"},
      {"WheelLoadHuge", Base::kSmall, "/vehicles/0/params/static_load", "1e300",
       "/vehicles/0/params/static_load: must be in [0, 1e+06], got 1e+300", "heavy haul"},
      {"WheelRadiusTiny", Base::kSmall, "/vehicles/0/params/wheel_radius", "1e-9",
       "/vehicles/0/params/wheel_radius: must be in [0.1, 2], got 1e-09", "tram"},
      // The couplers (sdk/include/rumble/macro_steps.hpp, plugins/couplers/implicit).
      {"AdaptiveMinStepTiny", Base::kSmall, "/coupling/params/adaptive",
       R"({"min_step": 1e-300, "max_step": 1e-3})",
       "/coupling/params/adaptive/min_step: must be in [1e-07, 1], got 1e-300", "couples none"},
      {"ImplicitForceToleranceHuge", Base::kSmall, "/coupling",
       R"({"type": "implicit", "params": {"absolute_tolerance": {"footprint_force": 1e300}}})",
       "/coupling/params/absolute_tolerance/footprint_force: must be in (0, 1e+06], got 1e+300",
       "footprint carries"},
  };
  return cases;
}

// gtest names a failing case by this rather than by the struct's bytes.
void PrintTo(const HostileCase& c, std::ostream* os) {
  *os << c.name << ": --set " << c.pointer << "=" << c.value;
}

class HostileValue : public ::testing::TestWithParam<HostileCase> {};

TEST_P(HostileValue, IsRefusedAtOnceNamingPointerValueAndRange) {
  const HostileCase& c = GetParam();
  const auto dir = scratch_directory(std::string("hostile_") + c.name);
  const nlohmann::json base = c.base == Base::kFem ? small_fem_scenario() : small_scenario();
  const std::string scenario = write_scenario(dir, base).string();
  const auto start = std::chrono::steady_clock::now();
  const CliResult r =
      run_rumble({"validate", scenario, "--set", std::string(c.pointer) + "=" + c.value});
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_LT(seconds, kSecondsAtMost) << r.output;
  EXPECT_THAT(r.output, HasSubstr(std::string("error: ") + c.error + " (set by --set)"));
  EXPECT_THAT(r.output, HasSubstr("hint: ")) << "the reason for the range";
  EXPECT_THAT(r.output, HasSubstr(c.reason));
}

// gtest's own names for the cases: the table's (a lambda's parameter would shadow the macro's).
std::string hostile_case_name(const ::testing::TestParamInfo<HostileCase>& param) {
  return param.param.name;
}

INSTANTIATE_TEST_SUITE_P(Cli, HostileValue, ::testing::ValuesIn(hostile_cases()),
                         hostile_case_name);

// A relation the ranges cannot hold: a layer thin against a wide box, each in its range, would
// need billions of elements (thickness / pml.elements across it); the mesh's own size estimate
// samples a grid that such a layer falls between, so gmsh ran for hours. Refused by the soil
// before meshing, naming the key, the numbers and the fix.
TEST(HostileValues, AThinMatchedLayerAroundAWideBoxIsRefusedBeforeMeshing) {
  const auto dir = scratch_directory("hostile_thin_pml");
  const std::string scenario = write_scenario(dir, small_fem_scenario()).string();
  const auto start = std::chrono::steady_clock::now();
  const CliResult r =
      run_rumble({"validate", scenario, "--set", "/soil/params/mesh/shape=box", "--set",
                  "/soil/params/mesh/radius=1000", "--set",
                  R"(/soil/params/boundary={"type": "pml", "pml": {"thickness": 4}})"});
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_LT(seconds, kSecondsAtMost) << r.output;
  EXPECT_THAT(r.output,
              HasSubstr("fem: params/boundary/pml/thickness: a layer of this thickness in "
                        "elements of at most 0.5 m (thickness / pml.elements) around a box of "
                        "mesh.radius 1e+03 m needs at least 9.22e+08 degrees of freedom, more "
                        "than mesh.max_dofs = 3e+06"));
  EXPECT_THAT(r.output, HasSubstr("thicken the layer"));
}

// The table is what the issue asks for: at least 25 cases, each its own value.
TEST(HostileValues, AtLeastTwentyFiveCases) {
  EXPECT_GE(hostile_cases().size(), 25u);
}

}  // namespace rumble::testing::hostile_values
