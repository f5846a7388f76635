// The FEM soil's operators on a structured Kuhn box (kuhn_box.hpp), against what must hold
// exactly: rigid motions make no force, a linear displacement field is reproduced (patch test),
// the lumped mass is the body's mass, the power-iteration stable step is the Kuhn mesh's known
// 0.671 h / c_p (docs/numerics.md §4.1), the scheme is stable below it and not above, and without
// damping it conserves energy.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <vector>

#include "boundary/absorbing_boundary.hpp"
#include "mesh/kuhn_box.hpp"
#include "operator/csr_operator.hpp"
#include "operator/elasticity.hpp"
#include "random_state.hpp"
#include "settings_from_params.hpp"
#include "time/explicit_solver.hpp"
#include "wave_speeds.hpp"

namespace rumble::fem {
namespace {

FemSettings medium_soil() {
  FemSettings s =
      rumble::test::soil_settings(155e6, 0.3, 1800.0);  // docs/physics.md §1.4: medium soil
  return s;
}

Eigen::VectorXd field(const TetMesh& m, const Eigen::Matrix3d& G, const Eigen::Vector3d& c) {
  Eigen::VectorXd u(m.dof_count());
  for (Eigen::Index i = 0; i < m.node_count(); ++i) u.segment<3>(3 * i) = G * m.node(i) + c;
  return u;
}

Eigen::VectorXd times(CsrMatrix& K, const Eigen::VectorXd& u) {
  Eigen::VectorXd y(u.size());
  K.multiply_rows(u.data(), y.data(), 0, K.rows());
  return y;
}

ExplicitSolver free_solver(const TetMesh& m, const FemSettings& s,
                           StepPrecision precision = StepPrecision::kDouble) {
  return ExplicitSolver(assemble_stiffness(m, s), lumped_mass(m, s), {}, false,
                        std::vector<char>(m.node_count(), 0), 0.0, 0.0, 1, precision);
}

TEST(FemElasticity, RigidMotionsMakeNoForce) {
  const TetMesh m = kuhn_box(3, 0.5);
  CsrMatrix K = assemble_stiffness(m, medium_soil());
  Eigen::Matrix3d spin;  // small rotation: skew-symmetric gradient
  spin << 0.0, -0.3, 0.2, 0.3, 0.0, -0.1, -0.2, 0.1, 0.0;
  const Eigen::VectorXd u = field(m, spin, Eigen::Vector3d(1.0, -2.0, 0.5));
  const Eigen::VectorXd f = times(K, u);
  // Round-off of sums of ~40 terms of size |K| |u|: 1e-12 relative is far above it.
  const double scale = 155e6 * 0.5 * u.cwiseAbs().maxCoeff();
  EXPECT_LT(f.cwiseAbs().maxCoeff(), 1e-12 * scale);
}

TEST(FemElasticity, LinearFieldsAreInEquilibriumInside) {
  // Patch test: a uniform strain makes no force at interior nodes; the nodal forces over the
  // whole body sum to zero.
  const int n = 4;
  const TetMesh m = kuhn_box(n, 0.5);
  CsrMatrix K = assemble_stiffness(m, medium_soil());
  Eigen::Matrix3d G;
  G << 1e-3, 2e-4, -5e-4, 3e-4, -7e-4, 1e-4, 6e-4, -2e-4, 4e-4;
  const Eigen::VectorXd f = times(K, field(m, G, Eigen::Vector3d::Zero()));
  const double scale = 155e6 * 0.5 * 1e-3;  // E h |G|: a boundary node's force [N]
  int interior = 0;
  for (Eigen::Index i = 0; i < m.node_count(); ++i) {
    const Eigen::Vector3d x = m.node(i) / 0.5;
    if ((x.array() < 0.5).any() || (x.array() > n - 0.5).any()) continue;
    ++interior;
    EXPECT_LT(f.segment<3>(3 * i).norm(), 1e-12 * scale) << "node " << i;
  }
  EXPECT_EQ(interior, (n - 1) * (n - 1) * (n - 1));
  for (int c = 0; c < 3; ++c) {
    double total = 0.0;
    for (Eigen::Index i = 0; i < m.node_count(); ++i) total += f[3 * i + c];
    EXPECT_LT(std::abs(total), 1e-11 * scale);
  }
}

TEST(FemElasticity, StiffnessIsSymmetricAndMassIsTheBodysMass) {
  const TetMesh m = kuhn_box(3, 0.4);
  const FemSettings s = medium_soil();
  CsrMatrix K = assemble_stiffness(m, s);
  const std::int64_t n = K.rows();
  std::vector<double> dense(n * n, 0.0);
  double largest = 0.0;
  for (std::int64_t r = 0; r < n; ++r)
    for (std::int64_t k = K.row_start()[r]; k < K.row_start()[r + 1]; ++k) {
      dense[r * n + K.column()[k]] = K.value()[k];
      largest = std::max(largest, std::abs(K.value()[k]));
    }
  double asymmetry = 0.0;
  for (std::int64_t r = 0; r < n; ++r)
    for (std::int64_t c = 0; c < r; ++c)
      asymmetry = std::max(asymmetry, std::abs(dense[r * n + c] - dense[c * n + r]));
  EXPECT_LT(asymmetry, 1e-12 * largest);
  EXPECT_NEAR(lumped_mass(m, s).sum(), 1800.0 * std::pow(1.2, 3), 1e-9 * 1800.0);
}

// The explicit step's product (node_rows_dot: one node index per 3 x 3 block) is the compressed
// rows' product (row_dot: one column index per value), row by row, to round-off: the same
// products summed in another order, so within a few ulps of the sum of their magnitudes.
TEST(FemElasticity, TheBlockProductIsTheRowProduct) {
  const TetMesh m = kuhn_box(3, 0.4);
  const CsrMatrix K = assemble_stiffness(m, medium_soil());
  const Eigen::VectorXd x = Eigen::VectorXd::Random(K.rows());
  for (std::int32_t i = 0; i < m.node_count(); ++i) {
    double block[3];
    K.node_rows_dot(i, x.data(), block);
    for (int c = 0; c < 3; ++c) {
      const std::int64_t r = 3 * i + c;
      double magnitude = 0.0;
      for (std::int64_t k = K.row_start()[r]; k < K.row_start()[r + 1]; ++k)
        magnitude += std::abs(K.value()[k] * x[K.column()[k]]);
      EXPECT_NEAR(block[c], K.row_dot(r, x.data()), 1e-14 * magnitude) << "row " << r;
    }
  }
}

// A force jump reads the force at the loaded nodes only (the energy tests check that nothing is
// missed); a node listed twice would take a jump twice, so it is refused.
TEST(FemExplicit, ForceJumpsReadTheLoadedNodesOnly) {
  ExplicitSolver op = free_solver(kuhn_box(2, 0.5), medium_soil());
  EXPECT_THROW(op.set_loaded_nodes({3, 5, 3}), std::invalid_argument);
  op.set_loaded_nodes({5});
  Eigen::VectorXd f = Eigen::VectorXd::Zero(op.dofs());
  f[3 * 5 + 2] = 1e3;  // N
  f[3 * 7 + 2] = 1e3;  // (not a loaded node: never read)
  ExplicitState s = op.rest_state();
  op.force_jump(s, f);
  EXPECT_GT(s.a[3 * 5 + 2], 0.0);
  EXPECT_EQ(s.a[3 * 7 + 2], 0.0);
}

TEST(FemExplicit, StableStepOfTheKuhnBoxIs0671HOverCp) {
  const double h = 0.5;
  const FemSettings s = medium_soil();
  const double c_p = soils::wave_speeds(155e6, 0.3, 1800.0).pressure;
  for (int n : {4, 6}) {
    const ExplicitSolver op = free_solver(kuhn_box(n, h), s);
    // The solver keeps a 2 % margin on omega_max^2 (1 % on the step); docs/numerics.md §4.1 gives
    // three digits for the box; the boundary nodes of a small box shift the top of the spectrum a
    // little: 3 %.
    EXPECT_NEAR(op.stable_step() / (h / c_p), 0.671, 0.03 * 0.671) << "n = " << n;
  }
}

// A modulus far outside any soil's overflows the Lanczos iteration of the stable step; it used to
// hang `rumble validate` in the tridiagonal QR on NaN (issue #30 item 3), now it is refused.
TEST(FemExplicit, AnOverflowingStiffnessIsRefusedNotIterated) {
  FemSettings s = medium_soil();
  s.half_space = {1e300, 0.3, 1800.0};  // E [Pa], nu, rho [kg/m^3]
  try {
    free_solver(kuhn_box(2, 0.5), s);
    ADD_FAILURE() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("sets the stable step, is not finite"));
    EXPECT_THAT(e.what(), ::testing::HasSubstr("E, rho and the mesh sizes must be physical"));
  }
}

/// growth_from_random_state at dt = ratio x the stable step, on the medium soil's Kuhn box.
double energy_growth(double ratio, int steps) {
  const TetMesh m = kuhn_box(4, 0.5);
  const ExplicitSolver op = free_solver(m, medium_soil());
  return test::growth_from_random_state(op, ratio * op.stable_step(), steps);
}

TEST(FemExplicit, StableJustBelowTheStepAndUnstableAbove) {
  // Velocity Verlet conserves a modified energy, so the energy oscillates (strongly for the
  // highest modes near the limit) but does not grow; 10 % above the true limit (the step keeps
  // a 1 % margin) the top mode grows by a factor of about 1.5 per step.
  EXPECT_LT(energy_growth(0.97, 3000), 1.05);
  EXPECT_GT(energy_growth(1.12, 400), 1e6);
}

class FemExplicitPrecision : public ::testing::TestWithParam<StepPrecision> {};

TEST_P(FemExplicitPrecision, ConservesItsShadowEnergyExactlyWithoutDamping) {
  // Velocity Verlet on M w'' + K w = 0 conserves, step to step and to round-off,
  //   1/2 v^T M v + 1/2 w^T K w - dt^2/8 a^T M a   (a = -M^-1 K w),
  // the energy of its modified equation: a check of the step's algebra that a wrong sign or a
  // lagged term breaks at the first step. K read in single precision is still symmetric (an
  // entry and its transpose round alike), so it holds with that K too.
  const TetMesh m = kuhn_box(4, 0.5);
  const ExplicitSolver op = free_solver(m, medium_soil(), GetParam());
  ExplicitState s{Eigen::VectorXd::Random(m.dof_count()) * 1e-6,
                  Eigen::VectorXd::Zero(m.dof_count()),
                  Eigen::VectorXd::Zero(m.dof_count()),
                  {},
                  {}};
  const Eigen::VectorXd no_force = Eigen::VectorXd::Zero(m.dof_count());
  const double dt = 0.9 * op.stable_step();
  const auto shadow = [&] {
    double ama = 0.0;
    for (Eigen::Index k = 0; k < s.a.size(); ++k) ama += op.mass()[k / 3] * s.a[k] * s.a[k];
    return op.kinetic_energy(s) + op.strain_energy(s) - dt * dt / 8.0 * ama;
  };
  op.step(s, no_force, dt);  // a is the initial state's from here on
  const double e0 = shadow();
  for (int k = 0; k < 3000; ++k) op.step(s, no_force, dt);
  EXPECT_NEAR(shadow() / e0, 1.0, 1e-9);
}

INSTANTIATE_TEST_SUITE_P(BothPrecisions, FemExplicitPrecision,
                         ::testing::Values(StepPrecision::kDouble, StepPrecision::kSingle),
                         [](const auto& param_info) {
                           return param_info.param == StepPrecision::kSingle ? "single" : "double";
                         });

// K in single precision: each product within its rounding of the double one, the stable step
// the same, and a damped run with dashpots from a random state the same to the rounding's
// effect accumulated over its steps.
TEST(FemExplicit, SinglePrecisionStiffnessIsWithinItsRoundingOfDouble) {
  const TetMesh m = kuhn_box(4, 0.5);
  const FemSettings s = medium_soil();
  const TrackRegion centre{1.0, 1.0, 1.0, 1.0};
  const auto solver = [&](StepPrecision precision) {
    return ExplicitSolver(assemble_stiffness(m, s), lumped_mass(m, s),
                          absorbing_boundary(m, s, centre), true,
                          std::vector<char>(m.node_count(), 0), s.damping.mass_coefficient(),
                          s.damping.stiffness_coefficient(), 1, precision);
  };
  const ExplicitSolver dp = solver(StepPrecision::kDouble), sp = solver(StepPrecision::kSingle);
  EXPECT_EQ(sp.precision(), StepPrecision::kSingle);
  // Products: rounding to float moves each entry by at most 2^-24 of itself, so a row's product
  // by at most 2^-24 of the sum of its terms' magnitudes (plus double round-off, 1e-14 of it).
  const CsrMatrix& K = dp.stiffness();
  const Eigen::VectorXd x = Eigen::VectorXd::Random(K.rows());
  Eigen::VectorXd y_double, y_single;
  dp.effective_stiffness_times(x, y_double, 1.0);
  sp.effective_stiffness_times(x, y_single, 1.0);
  double largest_change = 0.0;  // over the bound
  for (std::int64_t r = 0; r < K.rows(); ++r) {
    double magnitude = 0.0;
    for (std::int64_t k = K.row_start()[r]; k < K.row_start()[r + 1]; ++k)
      magnitude += std::abs(K.value()[k] * x[K.column()[k]]);
    if (magnitude > 0.0)
      largest_change = std::max(largest_change, std::abs(y_single[r] - y_double[r]) /
                                                    ((std::ldexp(1.0, -24) + 1e-14) * magnitude));
  }
  EXPECT_LE(largest_change, 1.0);
  EXPECT_GT(largest_change, 0.0);  // the product did read the rounded values
  // The largest eigenvalue moves by the rounding (6e-8 relative) at most; Lanczos converges to
  // 1e-9.
  EXPECT_NEAR(sp.stable_step() / dp.stable_step(), 1.0, 1e-6);
  // 1000 damped steps from a random state: the difference grows at most by about omega_max dt
  // (about 1.6) times the rounding per step, 1000 x 1.6 x 6e-8 = 1e-4 of the state; measured
  // 1.7e-5 for w, 4.7e-6 for v.
  ExplicitState a = test::random_state(dp, 5), b = test::random_state(sp, 5);
  const Eigen::VectorXd no_force = Eigen::VectorXd::Zero(dp.dofs());
  const double dt = 0.8 * dp.stable_step();
  for (int k = 0; k < 1000; ++k) {
    dp.step(a, no_force, dt);
    sp.step(b, no_force, dt);
  }
  EXPECT_LT((a.w - b.w).norm() / a.w.norm(), 1e-4);
  EXPECT_LT((a.v - b.v).norm() / a.v.norm(), 1e-4);
  std::printf("[ measured ] single against double after 1000 steps: w %.2e, v %.2e\n",
              (a.w - b.w).norm() / a.w.norm(), (a.v - b.v).norm() / a.v.norm());
}

TEST(FemExplicit, BoundaryDashpotsTakeEnergyOut) {
  const TetMesh m = kuhn_box(4, 0.5);
  const FemSettings s = medium_soil();
  const TrackRegion centre{1.0, 1.0, 1.0, 1.0};
  const ExplicitSolver op(assemble_stiffness(m, s), lumped_mass(m, s),
                          absorbing_boundary(m, s, centre), true,
                          std::vector<char>(m.node_count(), 0), 0.0, 0.0, 1);
  // 2000 steps are ~ 60 crossings of the box by a P wave: the dashpots on five of six sides
  // take nearly all of it.
  EXPECT_LT(test::energy_after(op, 0.8 * op.stable_step(), 2001), 1e-3);
}

/// Another back end of the soil operator as the step sees one: every call through the virtual
/// interface (soil_operator.hpp), the step's product handed over in runs, no fast path.
class ForwardingOperator final : public SoilOperator {
 public:
  explicit ForwardingOperator(std::unique_ptr<CsrOperator> inner)
      : SoilOperator(inner->mass(), inner->boundary(), inner->springs_act(), inner->fixed(),
                     inner->threads()),
        inner_(std::move(inner)) {}
  void set_threads(unsigned threads) override {
    threads_ = threads;
    inner_->set_threads(threads);
  }
  void stiffness_times(const Eigen::VectorXd& x, Eigen::VectorXd& y,
                       bool with_springs) const override {
    inner_->stiffness_times(x, y, with_springs);
  }
  void stepped_stiffness_times(const Eigen::VectorXd& x, Eigen::VectorXd& y,
                               bool with_springs) const override {
    inner_->stepped_stiffness_times(x, y, with_springs);
  }
  void stepped_product(const double* x, NodeProducts& take) const override {
    inner_->stepped_product(x, take);
  }
  StepPrecision precision() const override { return inner_->precision(); }
  const CsrMatrix& stiffness() const override { return inner_->stiffness(); }
  std::size_t bytes() const override { return inner_->bytes(); }

 private:
  std::unique_ptr<CsrOperator> inner_;
};

// The step through the interface alone (a back end the step does not know) is the step on the
// CSR back end's fused product, bit for bit: with the boundary's springs and dashpots, two
// threads and K in float.
TEST(FemExplicit, AnotherBackEndStepsBitForBitAsTheCsrOne) {
  const TetMesh m = kuhn_box(4, 0.5);
  const FemSettings s = medium_soil();
  const TrackRegion centre{1.0, 1.0, 1.0, 1.0};
  const auto csr = [&] {
    return std::make_unique<CsrOperator>(
        assemble_stiffness(m, s), lumped_mass(m, s), absorbing_boundary(m, s, centre), true,
        std::vector<char>(m.node_count(), 0), 2, StepPrecision::kSingle);
  };
  const ExplicitSolver fused(csr(), 0.5, 1e-4);
  const ExplicitSolver forwarded(std::make_unique<ForwardingOperator>(csr()), 0.5, 1e-4);
  ASSERT_EQ(fused.stable_step(), forwarded.stable_step());
  ExplicitState a = test::random_state(fused, 3), b = test::random_state(forwarded, 3);
  const Eigen::VectorXd f = Eigen::VectorXd::Constant(fused.dofs(), 1e3);
  const double dt = 0.8 * fused.stable_step();
  for (int k = 0; k < 50; ++k) {
    fused.step(a, f, dt);
    forwarded.step(b, f, dt);
  }
  EXPECT_EQ(a.w, b.w);
  EXPECT_EQ(a.v, b.v);
  EXPECT_EQ(a.a, b.a);
}

}  // namespace
}  // namespace rumble::fem
