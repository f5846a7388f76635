// The static solve's two paths agree: the CHOLMOD factor (meshes up to
// StaticSolver::kFactorLimit DOFs) and Jacobi-preconditioned conjugate gradients (beyond it, here
// forced with a limit of 0), and CG started from the last solution needs fewer iterations when
// the engine's static iteration asks again with a slightly changed load.
#include "static_solver.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "absorbing_boundary.hpp"
#include "elasticity.hpp"
#include "kuhn_box.hpp"

namespace rumble::fem {
namespace {

TEST(FemStatics, ConjugateGradientsAgreeWithTheFactorAndStartFromTheLastSolution) {
  const TetMesh m = kuhn_box(4, 0.5);
  FemSettings s;
  s.half_space = {155e6, 0.3, 1800.0};  // physics.md §4.1, medium soil
  const TrackRegion centre{1.0, 1.0, 1.0, 1.0};
  const ExplicitSolver op(assemble_stiffness(m, s), lumped_mass(m, s),
                          absorbing_boundary(m, s, centre), true,
                          std::vector<char>(m.node_count(), 0), 0.0, 0.0, 1);
  const Eigen::VectorXd f = Eigen::VectorXd::Constant(op.dofs(), 1e3);  // N per DOF
  StaticSolver factor(op);
  StaticSolver cg(op, /*factor_limit=*/0);
  const Eigen::VectorXd u = factor.solve(f);
  const Eigen::VectorXd u_cg = cg.solve(f);
  EXPECT_TRUE(factor.factored());
  EXPECT_FALSE(cg.factored());
  // CG stops at a residual of 1e-10 of the load; the error is at most that times the
  // condition number of K + S (below 1e4 on this box with its springs).
  EXPECT_LT((u_cg - u).norm(), 1e-6 * u.norm());
  const int cold = cg.last_cg_iterations();
  const Eigen::VectorXd u2 = cg.solve(1.01 * f);  // from u_cg: 1 % of the residual left
  const int warm = cg.last_cg_iterations();
  RecordProperty("cg_iterations_cold", cold);
  RecordProperty("cg_iterations_warm", warm);
  EXPECT_LT((u2 - 1.01 * u).norm(), 1e-6 * u.norm());
  EXPECT_GT(cold, 10);
  EXPECT_LT(warm, cold);
  // No load: at rest, whatever came before.
  EXPECT_EQ(cg.solve(Eigen::VectorXd::Zero(op.dofs())).norm(), 0.0);
}

}  // namespace
}  // namespace rumble::fem
