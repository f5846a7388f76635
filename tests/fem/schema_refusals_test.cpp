// What the FEM soil's params schema refuses itself, checked as the host checks it (the engine's
// SchemaChecker on the params as the user wrote them, before the defaults are filled): the
// ranges, which read_settings no longer repeats, and the settings that only one value of another
// key uses (boundary.pml, boundary.alpha_normal, damping.mechanisms), whose defaults are filled
// only with that value, so that params with their defaults filled in validate again.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "scenario/schema_check.hpp"
#include "soil_harness.hpp"

namespace rumble::test {
namespace {

using nlohmann::json;

const scenario::SchemaChecker& fem_schema() {
  static const scenario::SchemaChecker checker(soil_factory("fem").params_schema);
  return checker;
}

/// The schema's refusals of params, as the engine words them after its pointer
/// ("params/courant: must be in (0, 1], got 1.5"), one per line; "" when it takes them.
std::string refusals(const json& params) {
  std::string out;
  for (const scenario::SchemaIssue& issue : fem_schema().check(params)) {
    out += (out.empty() ? "" : "\n") + std::string("params") + issue.pointer + ": " + issue.message;
    if (issue.show_value) out += ", got " + params.at(json::json_pointer(issue.pointer)).dump();
  }
  return out;
}

json small_soil() {
  return {{"E", 750e6}, {"nu", 0.3}, {"rho", 1800.0}};
}

TEST(FemSchema, RefusesTheRangesTheSettingsNoLongerCheck) {
  json p = small_soil();
  p["courant"] = 1.5;
  EXPECT_EQ(refusals(p), "params/courant: must be in (0, 1], got 1.5");
  p = small_soil();
  p["mesh"] = {{"radius", 0.0}, {"f_max", 0.0}};
  EXPECT_EQ(refusals(p),
            "params/mesh/f_max: must be in [1, 2000], got 0.0\n"
            "params/mesh/radius: must be in [1, 1000], got 0.0");
  p = small_soil();
  p["mesh"] = {{"refine", 4}};  // (512 tetrahedra per coarse one at 3 already)
  EXPECT_EQ(refusals(p), "params/mesh/refine: must be in [0, 3], got 4");
  p["mesh"] = {{"refine", 1.5}};
  EXPECT_NE(refusals(p), "");
}

// The soil's own multigrid was removed (docs/decisions/0018-petsc-statics.md): a scenario that
// still names it is refused with the values there are and what replaces it.
TEST(FemSchema, TheRemovedMultigridStaticsAreRefusedWithWhatReplacesThem) {
  json p = small_soil();
  p["statics"] = {{"solver", "multigrid"}};
  EXPECT_EQ(refusals(p),
            "params/statics/solver: must be one of: auto, gamg, geometric, aggregation, got "
            "\"multigrid\"");
  const std::vector<scenario::SchemaIssue> issues = fem_schema().check(p);
  ASSERT_EQ(issues.size(), 1u);
  EXPECT_EQ(issues[0].hint,  // (the schema's "x-removed", not "did you mean")
            "\"multigrid\" (the soil's own multigrid) was removed on 2026-12-06: \"auto\" "
            "replaces it, PETSc's GAMG or the geometric multigrid "
            "(docs/decisions/0018-petsc-statics.md)");
  p["statics"] = {{"solver", "auto"}};
  EXPECT_EQ(refusals(p), "");
}

TEST(FemSchema, AMatchedLayersSettingsUnderAnotherBoundaryAreRefused) {
  // They would be ignored.
  json p = small_soil();
  p["boundary"] = {{"pml", {{"thickness", 2.0}}}};
  EXPECT_EQ(refusals(p),
            "params/boundary/pml: sets the perfectly matched layer, but boundary.type is not "
            "\"pml\" (the layer would be ignored); set boundary.type \"pml\" or drop "
            "boundary.pml, got {\"thickness\":2.0}");
  p["boundary"]["type"] = "dashpot";
  EXPECT_NE(refusals(p), "");
  p["boundary"]["type"] = "pml";
  EXPECT_EQ(refusals(p), "");
}

TEST(FemSchema, LiusNormalSpringUnderTheHalfSpaceSpringsIsRefused) {
  // It would be ignored: the half-space springs are fitted to the field.
  json p = small_soil();
  p["boundary"] = {{"alpha_normal", 2.0}};
  const std::string refused =
      "params/boundary/alpha_normal: sets Liu's normal springs, but boundary.springs is "
      "\"half_space\" (springs fitted to the half-space's static field: docs/fem-soil.md "
      "section 3.2); set boundary.springs \"liu\" or drop alpha_normal, got 2.0";
  EXPECT_EQ(refusals(p), refused);
  p["boundary"]["springs"] = "half_space";
  EXPECT_EQ(refusals(p), refused);
  p["boundary"]["springs"] = "liu";
  EXPECT_EQ(refusals(p), "");
}

TEST(FemSchema, MaxwellMechanismsUnderRayleighsModelAreRefused) {
  json p = small_soil();
  p["damping"] = {{"mechanisms", 4}};
  EXPECT_EQ(refusals(p),
            "params/damping/mechanisms: sets the Maxwell mechanisms, but damping.model is "
            "\"rayleigh\"; set damping.model \"maxwell\" or drop damping.mechanisms, got 4");
  p["damping"]["model"] = "maxwell";
  EXPECT_EQ(refusals(p), "");
}

TEST(FemSchema, TheDependentDefaultsAreFilledOnlyWhereTheyApplyAndFilledParamsValidateAgain) {
  json plain = small_soil();
  fem_schema().fill_defaults(plain);
  EXPECT_FALSE(plain.at("boundary").contains("pml")) << plain.dump();
  EXPECT_FALSE(plain.at("boundary").contains("alpha_normal")) << plain.dump();
  EXPECT_FALSE(plain.at("damping").contains("mechanisms")) << plain.dump();
  EXPECT_EQ(plain.at("courant"), 0.9);
  EXPECT_EQ(refusals(plain), "");
  json chosen = small_soil();
  chosen["boundary"] = {{"type", "pml"}, {"springs", "liu"}};
  chosen["damping"] = {{"model", "maxwell"}};
  fem_schema().fill_defaults(chosen);
  EXPECT_EQ(chosen.at("boundary").at("pml"), (json{{"reflection", 0.01}, {"elements", 8}}));
  EXPECT_EQ(chosen.at("boundary").at("alpha_normal"), 4.0 / 3.0);
  EXPECT_EQ(chosen.at("damping").at("mechanisms"), 3);
  EXPECT_EQ(refusals(chosen), "");
}

TEST(FemSchema, ParamsWithoutTheSchemasDefaultsAreReadAgainstTheSchema) {
  // The host fills them; a caller of the C table that does not still gets a soil, since the soil
  // reads its params against its schema (rumble::Params), under each choice with its own
  // defaults (tests/fem/settings_defaults_test.cpp compares the values).
  const rumble_factory& f = soil_factory("fem");
  rumble_host host{};
  host.struct_size = sizeof(rumble_host);
  host.abi_minor = RUMBLE_ABI_MINOR;
  host.scenario_dir = ".";
  json pml = small_soil();
  pml["boundary"] = {{"type", "pml"}, {"springs", "liu"}};
  pml["mesh"] = {{"shape", "box"}};
  pml["damping"] = {{"model", "maxwell"}};
  for (const json& params : {small_soil(), pml}) {
    rumble_instance* instance = nullptr;
    const char* error = nullptr;
    ASSERT_EQ(f.create(params.dump().c_str(), &host, &instance, &error), RUMBLE_OK)
        << params.dump() << ": " << (error != nullptr ? error : "");
    static_cast<const rumble_soil_api*>(f.api)->common.destroy(instance);
  }
}

}  // namespace
}  // namespace rumble::test
