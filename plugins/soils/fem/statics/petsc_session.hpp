// PETSc, and MPI through it, for the statics' algebraic multigrid (petsc_static_solver.hpp):
// started on first use, once per process, and only in a process that solves with it. OpenMPI's
// initialisation takes 0.3-0.5 s on this machine and "leaks" about 120 KB by AddressSanitizer's
// count (docs/toolchain.md §9), so a run whose statics take the CHOLMOD factor never starts it.
//
// MPI: when the host has initialised MPI already (a future host under mpirun), PETSc initialises
// on it and neither starts nor finalises MPI (PetscInitialize asks MPI_Initialized first); else
// PETSc starts MPI as one rank (a singleton: no mpirun needed) and finalises it with itself. So
// is PETSc itself: when something else in the process started it, this session leaves it alone.
//
// Finalisation happens once, when the process ends or the plugin is unloaded, whichever comes
// first: the session is a function-local static of this library, whose destructor glibc
// registers with the library's own handle (__cxa_atexit), so dlclose runs it before the code
// goes (docs/toolchain.md §3: an object must not outlive its library) and exit runs it when
// Rumble never unloads the plugin. Never earlier: after MPI_Finalize MPI cannot start again in
// the process, so finalising when the last solver goes would break the next run's statics in
// the same process (a study, a test binary). Each solver holds a reference, so PetscFinalize
// waits for one that outlives the static. When the host has finalised MPI by then, PETSc's
// objects are left to the process's end (PETSc cannot finalise without MPI).
#pragma once

#include <memory>

namespace rumble::fem {

class PetscSession {
 public:
  /// The process's session, PETSc initialised on the first call (options: "-no_signal_handler",
  /// PETSc's handlers would take SIGSEGV, SIGFPE and SIGTERM from the host; "-skip_petscrc", a
  /// stray petscrc must not change the solver; the PETSC_OPTIONS variable is read, for tuning).
  /// Throws std::runtime_error when PETSc does not start.
  static std::shared_ptr<PetscSession> get();
  ~PetscSession();
  PetscSession(const PetscSession&) = delete;
  PetscSession& operator=(const PetscSession&) = delete;

  /// Whether get() has been called in this process (the factor's path never calls it).
  static bool started();

  /// Whether this session initialised PETSc (false: the host had, and finalises it).
  bool owns_petsc() const { return owns_petsc_; }

 private:
  PetscSession();
  bool owns_petsc_ = false;
};

/// A process-wide PETSc option (MatPtAP and MatMatMult read theirs without a prefix) set for this
/// object's lifetime unless PETSC_OPTIONS gave it, cleared after. The session must be started.
class ScopedPetscOption {
 public:
  ScopedPetscOption(const char* name, const char* value);
  ~ScopedPetscOption();
  ScopedPetscOption(const ScopedPetscOption&) = delete;
  ScopedPetscOption& operator=(const ScopedPetscOption&) = delete;

 private:
  const char* name_;
  bool set_ = false;  // (by this object: cleared by it)
};

/// GAMG's set-up frees each Galerkin product's intermediates (A P's rows, on many ranks P's rows
/// from the others, ...) once it is formed: PETSc keeps them to form the product again from a
/// changed matrix, which the statics never do. At 1.0e6 DOFs on 2 ranks a rank's peak fell from
/// 2.25 to 1.94 GB, and what it holds through the solves from 2.25 to 1.39 GB, with the same
/// hierarchy and iterations (docs/fem-soil.md §8). Set for the span of a set-up with
/// ScopedPetscOption(kClearProducts, "true").
inline constexpr const char* kClearProducts = "-mat_product_clear";

/// Throws std::runtime_error naming `what` and PETSc's message when code is not 0.
void petsc_check(int code, const char* what);

}  // namespace rumble::fem
