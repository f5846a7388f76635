// read_settings reads a default the host did not fill from the FEM soil's schema itself
// (rumble::Params), so that params filled by the engine's checker and params as a direct caller
// of the C API wrote them give the same settings: each default is written once, in the schema
// (fem_schema.cpp), including those only one choice of another key has (its if/then).
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "fem_schema.hpp"
#include "fem_settings.hpp"
#include "scenario/schema_check.hpp"

namespace rumble::test {
namespace {

using nlohmann::json;

json filled(json params) {
  static const scenario::SchemaChecker checker(fem::settings_schema());
  checker.fill_defaults(params);
  return params;
}

TEST(FemSettingsDefaults, UnfilledParamsReadTheSchemasDefaults) {
  const json params = {{"E", 750e6}, {"nu", 0.3}, {"rho", 1800.0}};
  const fem::FemSettings unfilled = fem::read_settings(params.dump());
  const fem::FemSettings host = fem::read_settings(filled(params).dump());
  EXPECT_EQ(unfilled.mesh.f_max, host.mesh.f_max);
  EXPECT_EQ(unfilled.mesh.radius, host.mesh.radius);
  EXPECT_EQ(unfilled.mesh.max_dofs, host.mesh.max_dofs);
  EXPECT_EQ(unfilled.courant, host.courant);
  EXPECT_EQ(unfilled.boundary.kind, fem::BoundaryKind::kViscousSpring);
  EXPECT_EQ(unfilled.damping.maxwell, host.damping.maxwell);
  EXPECT_EQ(unfilled.receptance.duration, host.receptance.duration);
  EXPECT_EQ(unfilled.local_steps, host.local_steps);
  EXPECT_EQ(unfilled.geometric_statics, host.geometric_statics);
  EXPECT_EQ(unfilled.statics_named, host.statics_named);
  // statics.solver "auto": without mesh.refine's nested meshes GAMG on one process and the
  // aggregation multigrid on the ranks (docs/fem-soil.md §7.1, §8), not named, so under mpirun
  // rank 0 factors below the limit.
  EXPECT_FALSE(host.geometric_statics);
  EXPECT_TRUE(host.aggregation_statics);
  EXPECT_FALSE(host.statics_named);
  const fem::FemSettings gamg = fem::read_settings(
      json{{"E", 750e6}, {"nu", 0.3}, {"rho", 1800.0}, {"statics", {{"solver", "gamg"}}}}.dump());
  EXPECT_FALSE(gamg.geometric_statics);
  EXPECT_FALSE(gamg.aggregation_statics);  // (GAMG on PETSc's copy of K on the ranks too)
  EXPECT_TRUE(gamg.statics_named);
  const fem::FemSettings aggregation = fem::read_settings(json{
      {"E", 750e6},
      {"nu", 0.3},
      {"rho", 1800.0},
      {"statics", {{"solver", "aggregation"}}}}.dump());
  EXPECT_TRUE(aggregation.aggregation_statics);
  EXPECT_TRUE(aggregation.statics_named);
}

TEST(FemSettingsDefaults, AutoStaticsTakeTheGeometricMultigridWhereTheMeshIsRefined) {
  const json refined = {{"E", 750e6}, {"nu", 0.3}, {"rho", 1800.0}, {"mesh", {{"refine", 1}}}};
  const fem::FemSettings s = fem::read_settings(refined.dump());
  EXPECT_TRUE(s.geometric_statics);
  EXPECT_FALSE(s.aggregation_statics);
  EXPECT_FALSE(s.statics_named);
  json named = refined;
  named["statics"] = {{"solver", "gamg"}};  // (named: as asked, on the refined mesh too)
  EXPECT_FALSE(fem::read_settings(named.dump()).geometric_statics);
  json from_file = refined;  // (a mesh file has no coarse level: GAMG)
  from_file["mesh"]["file"] = "soil.msh";
  const fem::FemSettings f = fem::read_settings(from_file.dump());
  EXPECT_FALSE(f.geometric_statics);
}

TEST(FemSettingsDefaults, ADefaultOnlyOneChoiceHasFollowsThatChoice) {
  const json params = {{"E", 750e6},
                       {"nu", 0.3},
                       {"rho", 1800.0},
                       {"mesh", {{"shape", "box"}}},
                       {"boundary", {{"type", "pml"}, {"springs", "liu"}}},
                       {"damping", {{"model", "maxwell"}}}};
  const fem::FemSettings unfilled = fem::read_settings(params.dump());
  const fem::FemSettings host = fem::read_settings(filled(params).dump());
  EXPECT_EQ(unfilled.boundary.pml_reflection, host.boundary.pml_reflection);
  EXPECT_EQ(unfilled.boundary.pml_elements, host.boundary.pml_elements);
  EXPECT_EQ(unfilled.boundary.alpha_normal, host.boundary.alpha_normal);
  EXPECT_EQ(unfilled.damping.mechanisms, host.damping.mechanisms);
  EXPECT_GT(host.damping.mechanisms, 0) << "the host filled it under maxwell";
  EXPECT_GT(host.boundary.alpha_normal, 0.0) << "the host filled it under liu";
}

}  // namespace
}  // namespace rumble::test
