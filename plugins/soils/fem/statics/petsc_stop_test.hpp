// The operator's stop check (Ctrl-C) between the iterations of PETSc's CG, for the statics'
// PETSc solvers (petsc_static_solver.hpp, geometric_static_solver.hpp): PETSc's C frames cannot
// carry a C++ exception, so the check's exception is kept, CG told to stop, and the solver
// rethrows it after KSPSolve. Included by those solvers' .cpp files only (no header of the room
// includes PETSc's).
#pragma once

#include <petscksp.h>

#include <exception>

#include "operator/soil_operator.hpp"

namespace rumble::fem {

struct PetscStopTest {
  const SoilOperator* op = nullptr;
  void* default_test = nullptr;  // KSPConvergedDefault's context
  std::exception_ptr stopped;    // the stop check's exception, rethrown after KSPSolve
};

/// ksp's convergence test: op's stop check, then PETSc's default test (stop must outlive ksp).
/// Throws std::runtime_error when PETSc fails.
void set_stop_test(KSP ksp, const SoilOperator& op, PetscStopTest& stop);

}  // namespace rumble::fem
