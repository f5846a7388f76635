// Bad input gets an exact message: from the plugin through SoilInstance (the engine's wrapper
// adds who refused and where the data came from), and from the params schema through
// `rumble validate` (pointer, value, rule; one line per error).
#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "../../cli/cli_runner.hpp"
#include "core/errors.hpp"
#include "soil_rig.hpp"

namespace rumble::soiltest {
namespace {

/// what() of the ConfigError that `f` throws ("" when it throws none).
template <class F>
std::string config_error(F&& f) {
  try {
    f();
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

std::string plugin_path(const std::string& type) {
  return soil_type(type).library->path.string();
}

TEST(SoilInputErrors, ClmRefusesFootprintsNotEquallySpaced) {
  std::vector<rumble_footprint> layout = sleeper_row(4);
  layout[2].x = 1.3;  // m; 1.2 would keep the 0.6 m spacing
  SoilInstance clm(soil_type("clm"), "/soil", soil_properties(), ".");
  EXPECT_EQ(config_error([&] { clm.accept_layout(layout); }),
            "soil 'clm' (/soil): accept_layout failed: clm: footprints must be equally spaced "
            "along the track; footprint 2 is at x = 1.3 m, expected 1.2 m (spacing 0.6 m); the "
            "chain couples each footprint to its neighbours at one spacing (use winkler for "
            "other layouts); the layout comes from /track/sleepers (count, spacing, footprint)");
  // Its footprints do not interact, so winkler takes any layout.
  SoilInstance winkler(soil_type("winkler"), "/soil", soil_properties(), ".");
  EXPECT_NO_THROW(winkler.accept_layout(layout));
}

TEST(SoilInputErrors, WinklerRefusesBothDirectAndSoilParams) {
  const nlohmann::json params = {{"k", 1e8}, {"c", 2e5}, {"E", 155e6}};
  EXPECT_EQ(config_error([&] { SoilInstance s(soil_type("winkler"), "/soil", params, "."); }),
            "/soil: soil type 'winkler' refused its params: winkler: give either k and c "
            "(direct), or E, nu and rho (from soil properties), not both; got k and c with E "
            "(plugin " +
                plugin_path("winkler") + ")");
}

TEST(SoilInputErrors, ClmRefusesNeitherDirectNorSoilParams) {
  // m_f alone belongs to neither set: it may be given with either.
  for (const nlohmann::json& params : {nlohmann::json::object(), nlohmann::json{{"m_f", 300.0}}}) {
    EXPECT_EQ(config_error([&] { SoilInstance s(soil_type("clm"), "/soil", params, "."); }),
              "/soil: soil type 'clm' refused its params: clm: give either m_f, k_f, c_f, k_c "
              "and c_c (direct), or E, nu and rho (from soil properties); got neither (plugin " +
                  plugin_path("clm") + ")")
        << params.dump();
  }
}

/// `rumble validate` on small_scenario() with this soil: exit code and the error lines, each
/// without its "FILE:LINE:COLUMN: " prefix.
struct Validation {
  int exit_code = -1;
  std::vector<std::string> errors;
  std::string output;
};

Validation validate(const std::string& name, const nlohmann::json& soil) {
  namespace t = rumble::testing;
  nlohmann::json scenario = t::small_scenario();
  scenario["soil"] = soil;
  const auto file = t::write_scenario(t::scratch_directory(name), scenario);
  Validation v;
  const t::CliResult r = t::run_rumble({"validate", file.string()});
  v.exit_code = r.exit_code;
  v.output = r.output;
  std::istringstream lines(r.output);
  std::string line;
  while (std::getline(lines, line)) {
    const auto at = line.find(": error: ");
    if (line.rfind(file.string() + ":", 0) == 0 && at != std::string::npos)
      v.errors.push_back(line.substr(at + 2));
  }
  return v;
}

TEST(SoilInputErrors, SchemaRulesThroughValidate) {
  const struct {
    const char* name;
    nlohmann::json soil;
    const char* line;
  } cases[] = {
      {"winkler_negative_k",
       {{"type", "winkler"}, {"params", {{"k", -1e8}, {"c", 2e5}}}},
       "error: /soil/params/k: must be in [10000, 1e+13], got -100000000.0"},
      {"clm_zero_k_f",
       {{"type", "clm"},
        {"params", {{"m_f", 0.0}, {"k_f", 0.0}, {"c_f", 1e5}, {"k_c", 1e8}, {"c_c", 1e5}}}},
       "error: /soil/params/k_f: must be in [10000, 1e+13], got 0.0"},
      {"clm_nu_half",
       {{"type", "clm"}, {"params", {{"E", 155e6}, {"nu", 0.5}, {"rho", 1800.0}}}},
       "error: /soil/params/nu: must be in [0, 0.495], got 0.5"},
      {"winkler_nu_negative",
       {{"type", "winkler"}, {"params", {{"E", 155e6}, {"nu", -0.1}, {"rho", 1800.0}}}},
       "error: /soil/params/nu: must be in [0, 0.495], got -0.1"},
      // Direct parameters and soil properties are exclusive: the plugin would refuse the mix at
      // run time, validate refuses it first.
      {"winkler_k_c_with_E",
       {{"type", "winkler"}, {"params", {{"k", 1e8}, {"c", 2e5}, {"E", 155e6}}}},
       "error: /soil/params: gives k and c together with soil properties; give either k and c "
       "(direct) or E, nu and rho (from soil properties), not both, got "
       "{\"E\":155000000.0,\"c\":200000.0,"
       "\"k\":100000..."},
      {"clm_properties_with_k_c",
       {{"type", "clm"}, {"params", {{"E", 155e6}, {"nu", 0.3}, {"rho", 1800.0}, {"k_c", 1e8}}}},
       "error: /soil/params: gives soil properties together with k_f, c_f, k_c or c_c; give "
       "either the five parameters (direct) or E, nu and rho (from soil properties, optionally "
       "with m_f), "
       "not both, got {\"E\":155000000.0,\"k_c\":100000000.0,\"nu\":..."},
  };
  for (const auto& c : cases) {
    const Validation v = validate(std::string("soil_schema_") + c.name, c.soil);
    EXPECT_EQ(v.exit_code, 1) << v.output;
    EXPECT_EQ(v.errors, std::vector<std::string>{c.line}) << v.output;
    EXPECT_NE(v.output.find("\n1 error\n"), std::string::npos) << v.output;
  }
}

}  // namespace
}  // namespace rumble::soiltest
