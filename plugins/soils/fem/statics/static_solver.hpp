// The static state: (K + S) u = f with the truncation surface held by the boundary springs (or
// fixed). A sparse Cholesky factor from CHOLMOD's 64-bit interface (cholmod_l, docs/toolchain.md §4
// and docs/numerics.md §4.2: the int interface fails near 1e6 DOFs), computed once and reused by
// every solve (the engine iterates the static state with the track); above kFactorLimit DOFs, where
// the factor would take more memory than the soil itself by far, PETSc's conjugate gradients
// preconditioned by its algebraic multigrid GAMG (petsc_static_solver.hpp) or by a geometric
// multigrid on mesh.refine's nested meshes (geometric_static_solver.hpp). The soil's own
// smoothed-aggregation multigrid and CG, which these replaced, are gone
// (docs/decisions/0018-petsc-statics.md).
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <functional>
#include <memory>

#include "memory_model.hpp"
#include "operator/soil_operator.hpp"
#include "statics/coarse_level.hpp"
#include "statics/geometric_static_solver.hpp"
#include "statics/petsc_static_solver.hpp"

namespace rumble::fem {

/// The iterative path: PETSc's CG with GAMG or with the geometric multigrid of a refined mesh
/// (set_coarse_level; PETSc started at the first such solve, never before).
enum class CgPreconditioner { kGamg, kGeometric };

class StaticSolver {
 public:
  /// DOFs (memory_model.hpp: the factor's memory grows as n^1.45, 4.3 GB at 2.9e5 DOFs).
  static constexpr auto kFactorLimit = static_cast<Eigen::Index>(memory::kFactorLimitDofs);

  /// Uses the operator's K, boundary springs (always: they carry the static load) and fixed
  /// nodes; nodes: the mesh's coordinates [m] (GAMG's rigid-body modes). Factors on first
  /// use when op has at most factor_limit DOFs, else uses CG with the given preconditioner.
  StaticSolver(const SoilOperator& op, const Eigen::Matrix3Xd& nodes,
               Eigen::Index factor_limit = kFactorLimit,
               CgPreconditioner preconditioner = CgPreconditioner::kGamg);
  ~StaticSolver();
  StaticSolver(const StaticSolver&) = delete;
  StaticSolver& operator=(const StaticSolver&) = delete;

  /// u with (K + S) u = f on the free DOFs, 0 on fixed ones. Throws std::runtime_error when the
  /// matrix is not positive definite (a floating mesh) or CG does not converge. CG starts from
  /// the last solution (the engine's static iteration asks again with a slightly changed load).
  Eigen::VectorXd solve(const Eigen::VectorXd& f);
  bool factored() const { return factor_ != nullptr; }
  /// kGeometric: what builds the coarse level (coarse_level.hpp), called at the first iterative
  /// solve and again after release(). Without it such a solve throws std::logic_error.
  void set_coarse_level(std::function<CoarseLevel()> build) { coarse_level_ = std::move(build); }
  /// Frees what the solves keep (the factor, PETSc's solver and hierarchy), which the
  /// plugin does once the statics are done (at the first step: docs/fem-soil.md section 7.2); a
  /// later solve builds them again, the same, and starts CG from rest.
  void release();
  /// Memory the solves keep now [bytes]: the factor (CHOLMOD's count of its memory in use), K's
  /// rows GAMG took from the operator, the geometric multigrid's coarse level and vectors;
  /// PETSc's own objects (GAMG's hierarchies) are not counted.
  std::size_t bytes() const;
  int last_cg_iterations() const { return cg_iterations_; }
  /// Seconds the multigrid hierarchy took to build (0 before, or with the factor; the geometric
  /// multigrid's coarse level included).
  double multigrid_setup_seconds() const { return multigrid_seconds_; }
  /// Levels of either multigrid once built (the mesh's included), else 0.
  int multigrid_levels() const;
  /// What the path is, for the log: "CHOLMOD", "CG + GAMG (PETSc)", ...
  const char* method() const;

 private:
  struct Factor;
  Eigen::VectorXd factor_solve(const Eigen::VectorXd& f);
  /// kGamg's solve, its hierarchy built when missing.
  Eigen::VectorXd gamg_solve(const Eigen::VectorXd& f);
  /// kGeometric's solve, its levels built when missing.
  Eigen::VectorXd geometric_solve(const Eigen::VectorXd& f);

  const SoilOperator& op_;
  const Eigen::Matrix3Xd& nodes_;
  Eigen::Index factor_limit_;
  CgPreconditioner preconditioner_;
  std::unique_ptr<Factor> factor_;
  std::unique_ptr<PetscStaticSolver> gamg_;
  std::unique_ptr<GeometricStaticSolver> geometric_;
  std::function<CoarseLevel()> coarse_level_;
  int cg_iterations_ = 0;
  double multigrid_seconds_ = 0.0;
};

}  // namespace rumble::fem
