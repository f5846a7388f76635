// The static solve's factor path (meshes up to StaticSolver::kFactorLimit DOFs: CHOLMOD) keeps
// what it needs and frees it, never starts PETSc, and factors the lower triangle of the same
// combination the geometric multigrid's coarse level assembles whole; the plugin's Ctrl-C check
// ends the local steps' choice. PETSc's paths above the limit are checked in their own processes
// (gamg_statics_test.cpp, geometric_statics_test.cpp).
#include "statics/static_solver.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <optional>
#include <vector>

#include "boundary/absorbing_boundary.hpp"
#include "mesh/kuhn_box.hpp"
#include "operator/effective_matrix.hpp"
#include "operator/elasticity.hpp"
#include "settings_from_params.hpp"
#include "statics/petsc_session.hpp"
#include "time/explicit_solver.hpp"

namespace rumble::fem {
namespace {

/// A Kuhn box of n^3 cubes (medium soil), its sides on the viscous-spring boundary or, with
/// `fixed_bottom`, its bottom nodes held (identity rows, where the rigid-body modes vanish);
/// precision: how its explicit step reads K.
struct Box {
  Box(int n, bool fixed_bottom, StepPrecision precision = StepPrecision::kDouble)
      : mesh(kuhn_box(n, 0.25)), settings(rumble::test::soil_settings(155e6, 0.3, 1800.0)) {
    std::vector<char> fixed(mesh.node_count(), 0);
    for (Eigen::Index i = 0; i < mesh.node_count(); ++i)
      fixed[i] = fixed_bottom && mesh.nodes(2, i) > 0.25 * n - 1e-9;
    const double c = 0.125 * n;
    op.emplace(assemble_stiffness(mesh, settings), lumped_mass(mesh, settings),
               absorbing_boundary(mesh, settings, TrackRegion{c, c, c, c}), true, std::move(fixed),
               0.0, 0.0, 2, precision);
  }
  TetMesh mesh;
  FemSettings settings;
  std::optional<ExplicitSolver> op;
};

// What the factor keeps is freed once the statics are done (the plugin does it when the host's
// static iteration is over) and built again, the same, when a solve asks again: the factor
// (CHOLMOD's count of its memory), and K's rows, which the operator assembles again to the bit.
// This path never starts PETSc (and MPI with it: 0.3-0.5 s and a leak by AddressSanitizer's
// count, statics/petsc_session.hpp). (docs/fem-soil.md section 7.2: the stepping phase's memory;
// GAMG's path: gamg_statics_test.cpp.)
TEST(FemStatics, WhatTheFactorKeepsIsFreedAndBuiltAgainTheSame) {
  Box box(12, true, StepPrecision::kSingle);
  ExplicitSolver& op = *box.op;
  op.set_stiffness_source([&box] { return assemble_stiffness(box.mesh, box.settings); });
  const CsrMatrix K = op.stiffness();  // (a copy)
  const Eigen::VectorXd f = Eigen::VectorXd::Constant(op.dofs(), 1e3);
  const auto dofs = static_cast<std::size_t>(op.dofs());
  StaticSolver kept(op.soil(), box.mesh.nodes), released(op.soil(), box.mesh.nodes);
  const Eigen::VectorXd u = kept.solve(f);
  EXPECT_TRUE(released.solve(f) == u);
  EXPECT_TRUE(released.factored());
  EXPECT_GT(released.bytes(), 16 * dofs);  // the factor
  released.release();
  op.release_stiffness();
  EXPECT_EQ(released.bytes(), 0U);
  EXPECT_FALSE(op.soil().holds_stiffness());
  EXPECT_TRUE(released.solve(1.01 * f) == kept.solve(1.01 * f));
  const CsrMatrix& again = op.stiffness();
  EXPECT_EQ(again.value(), K.value());
  EXPECT_EQ(again.column(), K.column());
  EXPECT_EQ(again.row_start(), K.row_start());
  EXPECT_EQ(released.multigrid_levels(), 0);
  EXPECT_STREQ(released.method(), "CHOLMOD");
  EXPECT_FALSE(PetscSession::started());
}

// The geometric multigrid's coarse level takes the whole matrix in rows (full_combination),
// CHOLMOD its lower triangle
// (lower_combination): the same combination, with the boundary's blocks, the lumped mass and
// the fixed DOFs' identity rows. K is assembled symmetric to rounding (each element's B^T D B),
// so the mirrored triangle may differ from the other by a few ulps of the largest entry.
TEST(FemStatics, TheWholeCombinationIsTheLowerTriangleMirrored) {
  const Box box(3, true);
  const Combination c{.stiffness = 1.3, .mass = 7.0, .springs = true, .dashpots = 0.1};
  const Eigen::MatrixXd whole(full_combination(box.op->soil(), c));
  const LongSparse lower = lower_combination(box.op->soil(), c);
  const Eigen::MatrixXd mirrored(LongSparse(lower.selfadjointView<Eigen::Lower>()));
  ASSERT_EQ(whole.rows(), box.op->dofs());
  const double largest = whole.cwiseAbs().maxCoeff();
  EXPECT_LE((whole - mirrored).cwiseAbs().maxCoeff(), 1e-14 * largest);  // (measured: 0 here)
  const auto held = std::find(box.op->fixed().begin(), box.op->fixed().end(), 1);
  ASSERT_NE(held, box.op->fixed().end());
  const Eigen::Index dof = 3 * (held - box.op->fixed().begin()) + 2;
  EXPECT_EQ(whole.row(dof).cwiseAbs().sum(), 1.0);  // a held DOF: its identity row
  EXPECT_EQ(whole(dof, dof), 1.0);
}

// The plugin's Ctrl-C check (ExplicitSolver::set_stop_check) is called between the eigenvalue
// iterations of the local steps' choice, so a stop request ends a long choice with the check's
// exception, after as many iterations as the check allowed (PETSc's CG:
// gamg_statics_test.cpp).
TEST(FemStatics, TheStopCheckEndsTheLocalStepsChoice) {
  struct StopRequested {};
  const TetMesh m = kuhn_box(4, 0.5);
  FemSettings s = rumble::test::soil_settings(155e6, 0.3, 1800.0);
  const TrackRegion centre{1.0, 1.0, 1.0, 1.0};
  ExplicitSolver op(assemble_stiffness(m, s), lumped_mass(m, s), absorbing_boundary(m, s, centre),
                    true, std::vector<char>(m.node_count(), 0), 0.0, 0.0, 1);
  int calls = 0;
  op.set_stop_check([&calls] {
    if (++calls == 5) throw StopRequested{};
  });
  EXPECT_THROW(op.enable_local_steps(2), StopRequested);
  EXPECT_EQ(calls, 5);
}

}  // namespace
}  // namespace rumble::fem
