#include "statics/petsc_session.hpp"

#include <mpi.h>
#include <petscsys.h>

#include <atomic>
#include <stdexcept>
#include <string>

namespace rumble::fem {

namespace {

// The first message of PETSc's last error (where it was raised; the calls it passed through
// add nothing a user needs): PETSc's default handler prints a traceback to stderr, which a
// host's log would interleave with its own lines; the soil throws the message instead.
thread_local std::string petsc_last_error;

std::atomic<bool> session_started{false};

PetscErrorCode keep_petsc_message(MPI_Comm, int, const char* function, const char*,
                                  PetscErrorCode code, PetscErrorType type, const char* message,
                                  void*) {
  if (type == PETSC_ERROR_INITIAL)
    petsc_last_error = std::string(message ? message : "") + " (in " + function + ")";
  return code;
}

}  // namespace

PetscSession::PetscSession() {
  PetscBool started = PETSC_FALSE;
  petsc_check(PetscInitialized(&started), "PetscInitialized");
  if (started) return;  // the host's PETSc: its options and handlers stay
  static char name[] = "rumble", no_signals[] = "-no_signal_handler", no_rc[] = "-skip_petscrc";
  static char* arguments[] = {name, no_signals, no_rc, nullptr};
  int count = 3;
  char** argv = arguments;
  if (PetscInitialize(&count, &argv, nullptr, nullptr) != 0)
    throw std::runtime_error("fem: PETSc (and MPI) did not start (PetscInitialize failed)");
  owns_petsc_ = true;
  PetscPushErrorHandler(keep_petsc_message, nullptr);
  // GAMG's Galerkin products P^T A P by PETSc's "scalable" algorithm, which forms no transpose
  // of P: on the stiff example at 8.8e5 DOFs on one process the statics' peak was 2.6 kB per
  // DOF against 3.9 kB by forming P^T first ("rap"), whose set-up had been 1.7-2x faster at
  // 2.1e5 DOFs (docs/fem-soil.md §7.1). A process-wide option, as MatPtAP reads it without a
  // prefix; PETSC_OPTIONS may still choose another.
  PetscBool chosen = PETSC_FALSE;
  petsc_check(PetscOptionsHasName(nullptr, nullptr, "-matptap_via", &chosen),
              "PetscOptionsHasName");
  if (!chosen)
    petsc_check(PetscOptionsSetValue(nullptr, "-matptap_via", "scalable"), "PetscOptionsSetValue");
}

PetscSession::~PetscSession() {
  if (!owns_petsc_) return;
  int mpi_finalised = 0;
  MPI_Finalized(&mpi_finalised);
  if (!mpi_finalised) PetscFinalize();  // (and MPI_Finalize, when PETSc started MPI)
}

std::shared_ptr<PetscSession> PetscSession::get() {
  // Initialised once, thread-safely, on the first call; a failed start throws and the next
  // call tries again. Destroyed at exit or unload (petsc_session.hpp).
  static const std::shared_ptr<PetscSession> session(new PetscSession);
  session_started = true;
  return session;
}

bool PetscSession::started() {
  return session_started;
}

ScopedPetscOption::ScopedPetscOption(const char* name, const char* value) : name_(name) {
  PetscBool given = PETSC_FALSE;
  petsc_check(PetscOptionsHasName(nullptr, nullptr, name, &given), "PetscOptionsHasName");
  set_ = !given;
  if (set_) petsc_check(PetscOptionsSetValue(nullptr, name, value), "PetscOptionsSetValue");
}

ScopedPetscOption::~ScopedPetscOption() {  // (errors ignored: a destructor)
  if (set_) PetscOptionsClearValue(nullptr, name_);
}

void petsc_check(int code, const char* what) {
  if (code == 0) return;
  std::string message =
      "fem: PETSc failed in " + std::string(what) + " (error " + std::to_string(code) + ")";
  if (!petsc_last_error.empty()) message += ": " + petsc_last_error;
  petsc_last_error.clear();
  throw std::runtime_error(message);
}

}  // namespace rumble::fem
