// The explicit step gives the same numbers, to the bit, on any team size, also when the team
// changes between steps: what lets the soil choose its team from the machine's load as it goes
// (time/thread_tuner.hpp) without the results depending on the load. Each node's sums run in an
// order fixed by the blocks' parts, not by the threads (operator/symmetric_blocks.hpp). Checked
// on a Kuhn box with a stiff inclusion, with local time stepping and with K read in single
// precision.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <vector>

#include "inclusion_box.hpp"
#include "operator/elasticity.hpp"
#include "random_state.hpp"
#include "time/explicit_solver.hpp"

namespace rumble::fem {
namespace {

ExplicitSolver inclusion_solver(StepPrecision precision) {
  const TetMesh m = test::box_with_inclusion();
  const FemSettings s = test::inclusion_soil();
  return ExplicitSolver(assemble_stiffness(m, s), lumped_mass(m, s), {}, false,
                        std::vector<char>(m.node_count(), 0), 0.0, 1e-5, 1, precision);
}

/// The state after `steps` steps from a random one, under a load, with the team size of step k
/// given by team(k).
template <class Team>
ExplicitState team_stepped(ExplicitSolver& op, double dt, int steps, Team&& team) {
  ExplicitState s = test::random_state(op, 3);
  const Eigen::VectorXd f = Eigen::VectorXd::Constant(op.dofs(), 1e3);  // N
  for (int k = 0; k < steps; ++k) {
    op.set_threads(team(k));
    op.step(s, f, dt);
  }
  return s;
}

class TeamSize : public ::testing::TestWithParam<StepPrecision> {};

TEST_P(TeamSize, ChangesNoResultEvenBetweenSteps) {
  ExplicitSolver op = inclusion_solver(GetParam());
  ASSERT_TRUE(op.enable_local_steps(2));
  const double dt = op.stable_step();
  const ExplicitState one = team_stepped(op, dt, 60, [](int) { return 1u; });
  const ExplicitState two = team_stepped(op, dt, 60, [](int) { return 2u; });
  const ExplicitState mixed = team_stepped(op, dt, 60, [](int k) { return k % 3 == 0 ? 1u : 2u; });
  ASSERT_GT(one.w.norm(), 0.0);
  EXPECT_TRUE(one.w == two.w && one.v == two.v && one.a == two.a);
  EXPECT_TRUE(one.w == mixed.w && one.v == mixed.v && one.a == mixed.a);
}

INSTANTIATE_TEST_SUITE_P(ExplicitSteps, TeamSize,
                         ::testing::Values(StepPrecision::kDouble, StepPrecision::kSingle),
                         [](const ::testing::TestParamInfo<StepPrecision>& p) {
                           return p.param == StepPrecision::kDouble ? "Double" : "Single";
                         });

}  // namespace
}  // namespace rumble::fem
