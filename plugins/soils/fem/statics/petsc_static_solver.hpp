// The static solve (K + S) u = f by PETSc's conjugate gradients preconditioned by its smoothed-
// aggregation algebraic multigrid, GAMG (issue #33; docs/fem-soil.md §7.1, docs/numerics.md §4.4),
// on one rank (PETSC_COMM_SELF) for now: StaticSolver's path above its factor limit.
//
// The preconditioner's matrix is the operator's K + S in double, 3 DOFs per node (block size 3, so
// GAMG aggregates nodes, not single DOFs), fixed DOFs as identity rows and columns with a zero
// load; GAMG's near-null space is the six rigid-body modes from the node coordinates
// (MatNullSpaceCreateRigidBody): the displacements that cost elasticity no energy, which each
// aggregate's coarse basis must reproduce for the coarse levels to correct the smooth error the
// smoother leaves. CG stops when the residual of the true system, unpreconditioned, is 1e-10 of
// the load (the test of the hand-written CG it replaced), and starts from the last solution: the
// engine's static iteration asks again with a slightly changed load. The hierarchy is built once,
// by the constructor (StaticSolver's first solve), and kept (the matrix does not change).
//
// Options: GAMG with plain (unsmoothed) aggregation, which at 8.8e5 DOFs set up in a seventh of
// the time and half the memory of one smoothing of the prolongator, and solved the static start
// faster despite three times the iterations; Chebyshev(2) smoothing with Jacobi on each level
// (PETSc 3.18's default). Set before KSPSetFromOptions, so that PETSC_OPTIONS with the prefix
// "fem_statics_" overrides them for tuning (e.g. PETSC_OPTIONS="
// -fem_statics_pc_gamg_agg_nsmooths 1"; docs/fem-soil.md §7.1 has what was measured).
#pragma once

#include <Eigen/Core>
#include <memory>

#include "operator/soil_operator.hpp"

namespace rumble::fem {

class PetscStaticSolver {
 public:
  /// What CG's products and the mesh level's smoothing read. GAMG always sets up from K + S in
  /// compressed rows (AIJ, block size 3) in K's own arrays, taken from the operator
  /// (SoilOperator::take_stiffness: built again when the operator next needs them) with the
  /// springs added in place, so the statics hold no copy of K (0.5 GB at 1e6 DOFs).
  /// kSteppedProduct (the default): the operator's own threaded product (stepped_stiffness_times:
  /// K's upper blocks as the step reads them, in its precision, on the host's threads), which
  /// reads a sixth of the rows' bytes in single precision; the static state is then the one of
  /// the operator the dynamics step, which the soil starts from at rest. kAij: the AIJ rows, in
  /// double, on one thread.
  enum class Storage { kAij, kSteppedProduct };

  /// Builds the matrix and GAMG's hierarchy (PETSc started on first use, petsc_session.hpp).
  /// nodes: the mesh's coordinates [m], 3 x op.nodes(). Throws std::runtime_error when PETSc
  /// fails.
  PetscStaticSolver(const SoilOperator& op, const Eigen::Matrix3Xd& nodes,
                    Storage storage = Storage::kSteppedProduct);
  ~PetscStaticSolver();
  PetscStaticSolver(const PetscStaticSolver&) = delete;
  PetscStaticSolver& operator=(const PetscStaticSolver&) = delete;

  /// u with (K + S) u = f on the free DOFs, 0 on fixed ones, from the last solution. Throws
  /// std::runtime_error when CG does not converge; the operator's stop check (Ctrl-C) is called
  /// between iterations and its exception passes through.
  Eigen::VectorXd solve(const Eigen::VectorXd& f);
  int last_iterations() const { return iterations_; }
  /// Seconds the matrix and GAMG's hierarchy took (the constructor).
  double setup_seconds() const { return setup_seconds_; }
  /// GAMG's levels, the mesh's included.
  int levels() const { return levels_; }
  /// K + S's rows this solver took from the operator [bytes] (PETSc's AIJ shares them; its
  /// hierarchy is not counted).
  std::size_t bytes() const;
  /// Relative residual CG stops at (of the load on the free DOFs).
  static constexpr double kTolerance = 1e-10;

 private:
  struct Petsc;
  /// K's rows from the operator, made K + S in place (the constructor's first step).
  void take_rows(const SoilOperator& op);
  void make_stepped_product();
  void build_solver(const Eigen::Matrix3Xd& nodes);

  const SoilOperator& op_;
  std::unique_ptr<Petsc> petsc_;
  Eigen::VectorXd last_;
  int iterations_ = 0;
  int levels_ = 0;
  double setup_seconds_ = 0.0;
};

}  // namespace rumble::fem
