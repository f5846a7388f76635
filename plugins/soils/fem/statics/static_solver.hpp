// The static state: (K + S) u = f with the truncation surface held by the boundary springs (or
// fixed). A sparse Cholesky factor from CHOLMOD's 64-bit interface (cholmod_l, docs/toolchain.md §4
// and docs/numerics.md §4.2: the int interface fails near 1e6 DOFs), computed once and reused by
// every solve (the engine iterates the static state with the track); above kFactorLimit DOFs, where
// the factor would take more memory than the soil itself by far, PETSc's conjugate gradients
// preconditioned by its algebraic multigrid GAMG (petsc_static_solver.hpp, docs/numerics.md
// §4.4), set up at the first solve and kept likewise. Both solve K + S in double.
#pragma once

#include <Eigen/Core>
#include <memory>

#include "operator/soil_operator.hpp"
#include "statics/petsc_static_solver.hpp"

namespace rumble::fem {

class StaticSolver {
 public:
  static constexpr Eigen::Index kFactorLimit = 400000;  // DOFs: a factor of about 5 GB

  /// Uses the operator's K, boundary springs (always: they carry the static load) and fixed
  /// nodes; nodes: the mesh's coordinates [m] (GAMG's rigid-body modes). Factors on first use
  /// when op has at most factor_limit DOFs, else solves by CG with GAMG (PETSc started then, and
  /// only then: petsc_session.hpp).
  StaticSolver(const SoilOperator& op, const Eigen::Matrix3Xd& nodes,
               Eigen::Index factor_limit = kFactorLimit);
  ~StaticSolver();
  StaticSolver(const StaticSolver&) = delete;
  StaticSolver& operator=(const StaticSolver&) = delete;

  /// u with (K + S) u = f on the free DOFs, 0 on fixed ones. Throws std::runtime_error when the
  /// matrix is not positive definite (a floating mesh) or CG does not converge. CG starts from
  /// the last solution (the engine's static iteration asks again with a slightly changed load).
  Eigen::VectorXd solve(const Eigen::VectorXd& f);
  bool factored() const { return factor_ != nullptr; }
  /// CG's iterations in the last solve (0 with the factor).
  int last_cg_iterations() const { return gamg_ ? gamg_->last_iterations() : 0; }
  /// Seconds GAMG's matrices and hierarchy took to build (0 before, or with the factor).
  double multigrid_setup_seconds() const { return gamg_ ? gamg_->setup_seconds() : 0.0; }
  /// GAMG's levels once built (the mesh's included), else 0.
  int multigrid_levels() const { return gamg_ ? gamg_->levels() : 0; }
  /// The path op's size takes, for the log: "CHOLMOD" or "CG + GAMG (PETSc)".
  const char* method() const;

 private:
  struct Factor;

  const SoilOperator& op_;
  const Eigen::Matrix3Xd& nodes_;
  Eigen::Index factor_limit_;
  std::unique_ptr<Factor> factor_;
  std::unique_ptr<PetscStaticSolver> gamg_;
};

}  // namespace rumble::fem
