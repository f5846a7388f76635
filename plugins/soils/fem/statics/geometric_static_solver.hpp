// The static solve (K + S) u = f by PETSc's conjugate gradients preconditioned by a two-level
// geometric multigrid on mesh.refine's nested meshes (statics.solver "geometric"; issue #33,
// docs/fem-soil.md §7.1), on one process (PETSC_COMM_SELF).
//
// The fine level is the soil's mesh, matrix-free: a PETSc shell matrix over the operator's own
// threaded product (stepped_stiffness_times: K's upper blocks as the step reads them, in its
// precision), smoothed by Chebyshev(2) with Jacobi (the diagonal of K + S, the shell's
// MATOP_GET_DIAGONAL; the spectrum's bound estimated by 10 CG iterations, as GAMG estimates
// its levels'; statics/two_level_multigrid.hpp, shared with the ranks' solver). The coarse level
// is gmsh's mesh before its refinement with K + S assembled on it again (coarse_level.hpp: 1/8
// of the fine DOFs per level of mesh.refine), solved by one V-cycle
// of PETSc's algebraic multigrid GAMG (block size 3, the rigid-body modes of its nodes as the
// near-null space). The transfer is the nested linear elements' interpolation, exact for the
// coarse space, applied to the three components alike (MatCreateMAIJ), its transpose the
// restriction. So no fine matrix is assembled: the soil's double rows of K are freed before the
// set-up (the operator builds them again, the same, if a later call needs them), and the statics
// hold K's float blocks, the coarse level and CG's vectors.
//
// Held DOFs: identity rows of the shell, zero rows and columns of the interpolation. CG stops
// when the true residual is 1e-10 of the load on the free DOFs (as the other paths), starts
// from the last solution, and calls the operator's stop check between iterations. Options with
// the prefix "fem_statics_" (PETSC_OPTIONS) override the defaults for tuning, e.g.
// "-fem_statics_mg_levels_ksp_max_it 3" or "-fem_statics_mg_coarse_pc_type lu".
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <functional>
#include <memory>

#include "operator/soil_operator.hpp"
#include "statics/coarse_level.hpp"

namespace rumble::fem {

class GeometricStaticSolver {
 public:
  /// Builds the levels (PETSc started on first use, petsc_session.hpp): reads the diagonal of
  /// op's rows of K and frees them, then calls `coarse` for the coarse level (so the coarse
  /// mesh's assembly never meets the fine rows in memory). Throws std::runtime_error when PETSc
  /// fails, std::invalid_argument when the coarse level does not fit op.
  GeometricStaticSolver(const SoilOperator& op, const std::function<CoarseLevel()>& coarse);
  ~GeometricStaticSolver();
  GeometricStaticSolver(const GeometricStaticSolver&) = delete;
  GeometricStaticSolver& operator=(const GeometricStaticSolver&) = delete;

  /// u with (K + S) u = f on the free DOFs, 0 on held ones, from the last solution. Throws
  /// std::runtime_error when CG does not converge; the stop check's exception passes through.
  Eigen::VectorXd solve(const Eigen::VectorXd& f);
  int last_iterations() const { return iterations_; }
  /// Seconds the levels took to build (the constructor: the coarse GAMG's set-up included; the
  /// smoother's eigenvalue estimate is made at the first solve).
  double setup_seconds() const { return setup_seconds_; }
  /// The mesh's level and GAMG's levels below it.
  int levels() const { return levels_; }
  /// Memory held outside PETSc's own objects [bytes]: the coarse matrix and interpolation (which
  /// PETSc shares), the fine diagonal, the shell's and CG's start vectors.
  std::size_t bytes() const;
  static constexpr double kTolerance = 1e-10;

 private:
  struct Petsc;
  void make_levels();
  void build_solver();

  const SoilOperator& op_;
  std::unique_ptr<Petsc> petsc_;
  Eigen::VectorXd last_;
  int iterations_ = 0;
  int levels_ = 0;
  double setup_seconds_ = 0.0;
};

}  // namespace rumble::fem
