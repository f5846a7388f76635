// The static solve's paths agree: the CHOLMOD factor (meshes up to StaticSolver::kFactorLimit
// DOFs) and conjugate gradients (beyond it, here forced with a limit of 0) preconditioned by the
// diagonal or by smoothed-aggregation multigrid; CG started from the last solution needs fewer
// iterations when the engine's static iteration asks again with a slightly changed load, and
// multigrid needs far fewer than the diagonal.
#include "statics/static_solver.hpp"

#include <gtest/gtest.h>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "boundary/absorbing_boundary.hpp"
#include "memory_model.hpp"
#include "mesh/kuhn_box.hpp"
#include "operator/effective_matrix.hpp"
#include "operator/elasticity.hpp"
#include "sanitizer.hpp"
#include "settings_from_params.hpp"
#include "statics/amg_preconditioner.hpp"
#include "statics/mesh_matrix.hpp"
#include "statics/petsc_session.hpp"
#include "time/explicit_solver.hpp"

namespace rumble::fem {
namespace {

TEST(FemStatics, ConjugateGradientsAgreeWithTheFactorAndStartFromTheLastSolution) {
  const TetMesh m = kuhn_box(4, 0.5);
  FemSettings s =
      rumble::test::soil_settings(155e6, 0.3, 1800.0);  // docs/physics.md §1.4: medium soil
  const TrackRegion centre{1.0, 1.0, 1.0, 1.0};
  const ExplicitSolver op(assemble_stiffness(m, s), lumped_mass(m, s),
                          absorbing_boundary(m, s, centre), true,
                          std::vector<char>(m.node_count(), 0), 0.0, 0.0, 1);
  const Eigen::VectorXd f = Eigen::VectorXd::Constant(op.dofs(), 1e3);  // N per DOF
  StaticSolver factor(op.soil(), m.nodes);
  StaticSolver cg(op.soil(), m.nodes, /*factor_limit=*/0, CgPreconditioner::kJacobi);
  const Eigen::VectorXd u = factor.solve(f);
  const Eigen::VectorXd u_cg = cg.solve(f);
  EXPECT_TRUE(factor.factored());
  EXPECT_FALSE(cg.factored());
  // Neither path started PETSc (and MPI with it: 0.3-0.5 s and a leak by AddressSanitizer's
  // count, statics/petsc_session.hpp); only GAMG's does (gamg_statics_test.cpp, its own process).
  EXPECT_FALSE(PetscSession::started());
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

/// A Kuhn box of n^3 cubes (medium soil), its sides on the viscous-spring boundary or, with
/// `fixed_bottom`, its bottom nodes held (identity rows, where the rigid-body modes vanish);
/// precision: how its explicit step, and so multigrid's smoother on the mesh, reads K.
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

void expect_multigrid_agrees_and_beats_jacobi(bool fixed_bottom,
                                              StepPrecision precision = StepPrecision::kDouble) {
  const Box box(16, fixed_bottom, precision);  // 14 739 DOFs: two levels
  const ExplicitSolver& op = *box.op;
  Eigen::VectorXd f = Eigen::VectorXd::Zero(op.dofs());
  for (Eigen::Index i = 0; i < box.mesh.node_count(); ++i)  // 1 kN down on the top's centre
    if (box.mesh.nodes(2, i) == 0.0 && std::abs(box.mesh.nodes(0, i) - 2.0) <= 0.5 &&
        std::abs(box.mesh.nodes(1, i) - 2.0) <= 1.0)
      f[3 * i + 2] = 1e3;
  StaticSolver factor(op.soil(), box.mesh.nodes);
  StaticSolver multigrid(op.soil(), box.mesh.nodes, 0, CgPreconditioner::kMultigrid);
  StaticSolver jacobi(op.soil(), box.mesh.nodes, 0, CgPreconditioner::kJacobi);
  const Eigen::VectorXd u = factor.solve(f);
  const Eigen::VectorXd u_mg = multigrid.solve(f);
  jacobi.solve(f);
  ASSERT_NE(multigrid.multigrid(), nullptr);
  EXPECT_GE(multigrid.multigrid()->levels(), 2);
  EXPECT_GT(multigrid.multigrid_setup_seconds(), 0.0);  // (the soil logs it)
  EXPECT_EQ(factor.multigrid_setup_seconds(), 0.0);
  testing::Test::RecordProperty("multigrid_levels", multigrid.multigrid()->levels());
  testing::Test::RecordProperty("cg_iterations_multigrid", multigrid.last_cg_iterations());
  testing::Test::RecordProperty("cg_iterations_jacobi", jacobi.last_cg_iterations());
  std::printf("[ measured ] multigrid %d, jacobi %d CG iterations\n",
              multigrid.last_cg_iterations(), jacobi.last_cg_iterations());
  // As above: a residual of 1e-10 of the load, times the condition number of K + S (below 1e5
  // here: a 16^3 box), bounds the error.
  EXPECT_LT((u_mg - u).norm(), 1e-5 * u.norm());
  if (fixed_bottom) {
    for (Eigen::Index i = 0; i < box.mesh.node_count(); ++i)
      if (op.fixed()[i]) {
        EXPECT_EQ(u_mg.segment<3>(3 * i).norm(), 0.0);
      }
  }
  // Measured 58 against 299 iterations (springs) and 56 against 260 (fixed bottom), two levels;
  // the gap widens with the mesh (50 against 613 at 6.8e4 DOFs, 61 against 1448 at 9.4e5:
  // bench/fem/fem_static_bench.cpp). A third leaves room for another aggregation order.
  EXPECT_LT(3 * multigrid.last_cg_iterations(), jacobi.last_cg_iterations());
}

TEST(FemStatics, MultigridConjugateGradientsAgreeWithTheFactorInFarFewerIterations) {
  expect_multigrid_agrees_and_beats_jacobi(false);
}

TEST(FemStatics, MultigridHandlesFixedNodes) {
  expect_multigrid_agrees_and_beats_jacobi(true);
}

// The smoother's products on the mesh are the explicit step's (its threaded block rows), with K
// in single precision by default: a symmetric operator within 6e-8 of K + S, so the V-cycle
// stays a fixed symmetric preconditioner and CG converges as with K itself (measured: the same
// iteration counts, 58 and 56).
TEST(FemStatics, MultigridWithTheSinglePrecisionStepProductAgreesToo) {
  expect_multigrid_agrees_and_beats_jacobi(false, StepPrecision::kSingle);
  expect_multigrid_agrees_and_beats_jacobi(true, StepPrecision::kSingle);
}

// Multigrid set up from the mesh's matrix in K's own blocks, a chunk of aggregates at a time
// (mesh_matrix.hpp, mesh_coarsening.hpp, and the restriction from P's rows, transposed_product.hpp)
// is the hierarchy that the whole products make from full_combination, to the bit: its V-cycle
// gives the same vector, with the box's springs and with held nodes, on 1 and 2 threads, in one
// chunk and in chunks of 100 nodes (rows formed on both sides of the chunks' borders). It keeps
// no restriction beside the prolongator, so less memory.
TEST(FemStatics, MultigridFromKsBlocksInChunksIsTheWholeProductsHierarchyToTheBit) {
  for (const bool fixed_bottom : {false, true}) {
    const Box box(12, fixed_bottom, StepPrecision::kSingle);  // 6591 DOFs: two levels
    const ExplicitSolver& op = *box.op;
    const auto fine = [&op](const Eigen::VectorXd& x, Eigen::VectorXd& y) {
      op.stepped_stiffness_times(x, y, true);
    };
    Eigen::VectorXd r(op.dofs());
    for (Eigen::Index k = 0; k < r.size(); ++k) r[k] = std::sin(0.7 * static_cast<double>(k));
    for (const unsigned threads : {1u, 2u})
      for (const std::int64_t chunk : {kMeshChunkNodes, std::int64_t{100}}) {
        const AmgPreconditioner whole(
            full_combination(op.soil(), {.stiffness = 1.0, .springs = true}), box.mesh.nodes, fine,
            threads);
        const AmgPreconditioner chunked(MeshMatrix(op.soil().take_stiffness(), op.soil()),
                                        box.mesh.nodes, fine, threads, chunk);
        ASSERT_EQ(chunked.levels(), whole.levels());
        ASSERT_GE(chunked.levels(), 2);
        for (int l = 0; l < whole.levels(); ++l) EXPECT_EQ(chunked.dofs(l), whole.dofs(l));
        EXPECT_EQ(chunked.operator_complexity(), whole.operator_complexity());
        Eigen::VectorXd z_whole, z_chunked;
        whole.apply(r, z_whole);
        chunked.apply(r, z_chunked);
        ASSERT_EQ(z_chunked.size(), z_whole.size());
        EXPECT_EQ((z_chunked - z_whole).cwiseAbs().maxCoeff(), 0.0)
            << "fixed_bottom " << fixed_bottom << ", " << threads << " thread(s), chunks of "
            << chunk << " nodes";
        EXPECT_LT(chunked.bytes(), whole.bytes());
      }
  }
}

// What the statics keep is freed once they are done (the plugin does it when the host's static
// iteration is over) and built again, the same, when a solve asks again: the factor (CHOLMOD's
// count of its memory), the multigrid hierarchy, and K's rows, which multigrid takes over and
// the operator assembles again to the bit. (docs/fem-soil.md section 7.2: the stepping phase's
// memory.)
TEST(FemStatics, WhatTheStaticsKeepIsFreedAndBuiltAgainTheSame) {
  Box box(12, true, StepPrecision::kSingle);
  ExplicitSolver& op = *box.op;
  op.set_stiffness_source([&box] { return assemble_stiffness(box.mesh, box.settings); });
  const CsrMatrix K = op.stiffness();  // (a copy)
  const Eigen::VectorXd f = Eigen::VectorXd::Constant(op.dofs(), 1e3);
  const auto dofs = static_cast<std::size_t>(op.dofs());
  for (const Eigen::Index limit : {StaticSolver::kFactorLimit, Eigen::Index{0}}) {
    StaticSolver kept(op.soil(), box.mesh.nodes, limit), released(op.soil(), box.mesh.nodes, limit);
    const Eigen::VectorXd u = kept.solve(f);
    EXPECT_EQ(released.solve(f), u);
    EXPECT_GT(released.bytes(), 16 * dofs) << "limit " << limit;  // a factor or a hierarchy
    EXPECT_EQ(op.soil().holds_stiffness(), limit > 0);            // (multigrid took K's rows)
    released.release();
    op.release_stiffness();
    EXPECT_LE(released.bytes(), 8 * dofs);  // CG's last solution, its start next time
    EXPECT_FALSE(op.soil().holds_stiffness());
    EXPECT_EQ(released.solve(1.01 * f), kept.solve(1.01 * f)) << "limit " << limit;
    const CsrMatrix& again = op.stiffness();
    EXPECT_EQ(again.value(), K.value());
    EXPECT_EQ(again.column(), K.column());
    EXPECT_EQ(again.row_start(), K.row_start());
  }
}

// The process's resident memory now, and its peak since the last restart_peak() [bytes].
double resident_kib(const char* field) {
  std::ifstream status("/proc/self/status");
  std::string line;
  double kib = 0.0;
  while (std::getline(status, line))
    if (line.rfind(field, 0) == 0) std::istringstream(line.substr(6)) >> kib;
  return 1024.0 * kib;
}
bool restart_peak() {
  std::ofstream("/proc/self/clear_refs") << "5";  // (Linux >= 4.0: VmHWM := VmRSS)
  return resident_kib("VmHWM:") <= resident_kib("VmRSS:") + 4096.0 * 64;
}

// The soil's estimate of what its statics add at their peak (memory_model.hpp: 12.2 B per
// nonzero of K for multigrid's set-up), which its size() gives the host before the statics
// spend it, against what the set-up and first solve add to the resident memory, measured by
// the process's peak (VmHWM restarted before): within 25 % on a box of 2.1e5 DOFs (measured
// 0.95; on the stiff example at 1e6 DOFs the soil's whole-run estimate was 1.02 times the peak,
// docs/fem-soil.md section 7.2). Copying K for the set-up (0.6 times the estimate more), forming
// A P whole again (1.3 times), or chunks of 16384 nodes (measured: 2.1 times) fail it.
TEST(FemStatics, MultigridAddsTheMemoryTheModelEstimates) {
  if (rumble::test::kUnderAddressSanitizer)
    GTEST_SKIP() << "a sanitizer's allocator keeps freed blocks";
#if defined(__GLIBC__)
  // As the engine does after loading plugins (core/malloc_policy.hpp): this process links
  // PETSc, whose SuperLU_DIST turns malloc's return of freed memory off.
  ::mallopt(M_MMAP_MAX, 65536);
  ::mallopt(M_MMAP_THRESHOLD, 32 << 20);
  ::mallopt(M_TRIM_THRESHOLD, 64 << 20);
#endif
  Box box(40, false, StepPrecision::kSingle);
  ExplicitSolver& op = *box.op;
  op.set_stiffness_source([&box] { return assemble_stiffness(box.mesh, box.settings); });
  const auto dofs = static_cast<double>(op.dofs());
  const auto nonzeros = static_cast<double>(op.stiffness().nonzeros());
  const double estimate = memory::multigrid_bytes(nonzeros);
  StaticSolver statics(op.soil(), box.mesh.nodes, 0, CgPreconditioner::kMultigrid);
  Eigen::VectorXd f = Eigen::VectorXd::Zero(op.dofs());
  for (Eigen::Index i = 0; i < box.mesh.node_count(); ++i)
    if (box.mesh.nodes(2, i) == 0.0) f[3 * i + 2] = 1e3;
#if defined(__GLIBC__)
  ::malloc_trim(0);
#endif
  const double before = resident_kib("VmRSS:");
  if (!restart_peak()) GTEST_SKIP() << "this system does not let a process restart its peak";
  statics.solve(f);
  const double added = resident_kib("VmHWM:") - before;
  RecordProperty("statics_added_bytes", std::to_string(added));
  RecordProperty("statics_estimate_bytes", std::to_string(estimate));
  std::printf(
      "[ measured ] %.3g DOFs: the statics added %.3g MB at their peak, estimated %.3g MB\n", dofs,
      added / 1e6, estimate / 1e6);
  EXPECT_GT(added, 0.75 * estimate);
  EXPECT_LT(added, 1.25 * estimate);
}

// Multigrid takes the whole matrix in rows (full_combination), CHOLMOD its lower triangle
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

// The plugin's Ctrl-C check (ExplicitSolver::set_stop_check) is called between the conjugate
// gradients' iterations and between the eigenvalue iterations of the local steps' choice, so a
// stop request ends a long solve or choice with the check's exception, after as many iterations
// as the check allowed.
TEST(FemStatics, TheStopCheckEndsALongSolveAndTheLocalStepsChoice) {
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
  StaticSolver cg(op.soil(), m.nodes, /*factor_limit=*/0, CgPreconditioner::kJacobi);
  EXPECT_THROW(cg.solve(Eigen::VectorXd::Constant(op.dofs(), 1e3)), StopRequested);
  EXPECT_EQ(calls, 5);
  calls = 0;
  EXPECT_THROW(op.enable_local_steps(2), StopRequested);
  EXPECT_EQ(calls, 5);
}

}  // namespace
}  // namespace rumble::fem
