// What the statics' PETSc solvers (petsc_static_solver.hpp, geometric_static_solver.hpp) share
// around PETSc's CG (the ranks' statics, distributed/distributed_statics.hpp, too): its set-up,
// the stop check (Ctrl-C) between its iterations, agreed over the ranks, and one static
// solve with the warm start, the held DOFs and the failure's message; and the one-process shell
// product over the step's K with the held DOFs as identity. PETSc's C frames cannot
// carry a C++ exception, so the check's exception is kept, CG told to stop, and the solve
// rethrows it after KSPSolve. Included by those solvers' .cpp files and the ranks'
// (distributed/rank_petsc.hpp) only (no header of the statics room includes PETSc's).
#pragma once

#include <petscksp.h>

#include <Eigen/Core>
#include <exception>
#include <functional>

#include "operator/soil_operator.hpp"

namespace rumble::fem {

struct PetscStopTest {
  const SoilOperator* op = nullptr;
  /// The stop check, when not op's (the ranks': rank 0's asks the host, the others' nothing).
  std::function<void()> check;
  void* default_test = nullptr;  // KSPConvergedDefault's context
  std::exception_ptr stopped;    // the stop check's exception, rethrown after KSPSolve
  /// A product's failure on this rank (the ranks' shell product keeps it rather than fail inside
  /// PETSc's collective frames, distributed/geometric_rank_statics.cpp): CG ends at the next
  /// iteration on every rank, and the ranks agree on it after KSPSolve.
  std::exception_ptr failed;
};

/// PETSc's CG on comm for operator a, preconditioned from p: options prefix "fem_statics_", the
/// true (unpreconditioned) residual against `tolerance` of the load, as every static path tests
/// (static_solver.hpp), a nonzero initial guess (the warm start); its PC is the caller's to set.
/// Throws std::runtime_error when PETSc fails.
KSP static_cg(MPI_Comm comm, Mat a, Mat p, double tolerance);

/// ksp's convergence test: the stop check (stop.check, else op's), then PETSc's default test
/// (stop must outlive ksp). On a communicator of many ranks every rank learns at each iteration
/// whether any rank's check threw or product failed (one MPI_Allreduce), so that all leave CG
/// at the same iteration and none waits in its next sum; the caller then agrees on why
/// (distributed/rank_petsc.hpp's solve_on_ranks). Throws std::runtime_error when PETSc fails.
void set_stop_test(KSP ksp, const SoilOperator& op, PetscStopTest& stop);

/// One static solve by ksp (CG with a nonzero initial guess and set_stop_test's test, x and b
/// its vectors over f's size, their arrays placed for the call): u with (K + S) u = f on the
/// free DOFs, the load zeroed on op's held DOFs, from `last` (both updated); `iterations` the
/// CG iterations (0 at rest). Rethrows the stop check's exception; throws std::runtime_error
/// naming `method` (e.g. "CG with PETSc's GAMG") when CG does not converge.
Eigen::VectorXd solve_static(KSP ksp, Vec x, Vec b, PetscStopTest& stop, const Eigen::VectorXd& f,
                             Eigen::VectorXd& last, int& iterations, const char* method);

/// d = the values of `from` (of d's local size): a shell's MATOP_GET_DIAGONAL from a diagonal it
/// keeps (the fine levels of the geometric and aggregation multigrids). Returns PETSc's error.
PetscErrorCode copy_into(const Eigen::VectorXd& from, Vec d);

/// y = (K + S) x by op's threaded product, K as the step reads it; identity rows and columns on
/// op's held DOFs, as the assembled matrices have. The operator's product is 0 on a held node's
/// rows but reads x there, so x's held entries are taken out first: the product is then
/// symmetric for any x, as a smoother's spectrum estimate from a random x needs (with them, CG's
/// estimate of D^-1 (K + S) on a box held on five sides was 8.6e6, not 2.6). in, out: scratch of
/// x's size. For a MATSHELL's MATOP_MULT: returns PETSc's error for a C++ exception, which must
/// not cross PETSc's C frames.
PetscErrorCode held_stepped_product(const SoilOperator& op, Vec x, Vec y, Eigen::VectorXd& in,
                                    Eigen::VectorXd& out);

}  // namespace rumble::fem
