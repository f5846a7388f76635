#include "statics/petsc_cg.hpp"

#include <algorithm>
#include <sstream>
#include <stdexcept>
#include <utility>
#include <vector>

#include "statics/petsc_session.hpp"

namespace rumble::fem {

namespace {

PetscErrorCode converged_or_stopped(KSP ksp, PetscInt it, PetscReal rnorm,
                                    KSPConvergedReason* reason, void* context) {
  auto* test = static_cast<PetscStopTest*>(context);
  try {
    if (test->check)
      test->check();
    else if (test->op != nullptr)
      test->op->check_stop();
  } catch (...) {
    test->stopped = std::current_exception();
  }
  const MPI_Comm comm = PetscObjectComm(reinterpret_cast<PetscObject>(ksp));
  int ranks = 1;
  MPI_Comm_size(comm, &ranks);
  int stop = test->stopped || test->failed ? 1 : 0;
  if (ranks > 1) {
    int any = 0;
    PetscCallMPI(MPI_Allreduce(&stop, &any, 1, MPI_INT, MPI_MAX, comm));
    stop = any;
  }
  if (stop) {
    *reason = KSP_DIVERGED_ITS;
    return 0;
  }
  return KSPConvergedDefault(ksp, it, rnorm, reason, test->default_test);
}

}  // namespace

KSP static_cg(MPI_Comm comm, Mat a, Mat p, double tolerance) {
  KSP ksp = nullptr;
  petsc_check(KSPCreate(comm, &ksp), "KSPCreate");
  petsc_check(KSPSetOptionsPrefix(ksp, "fem_statics_"), "KSPSetOptionsPrefix");
  petsc_check(KSPSetOperators(ksp, a, p), "KSPSetOperators");
  petsc_check(KSPSetType(ksp, KSPCG), "KSPSetType");
  petsc_check(KSPSetNormType(ksp, KSP_NORM_UNPRECONDITIONED), "KSPSetNormType");
  petsc_check(KSPSetTolerances(ksp, tolerance, PETSC_DEFAULT, PETSC_DEFAULT, 20000),
              "KSPSetTolerances");
  petsc_check(KSPSetInitialGuessNonzero(ksp, PETSC_TRUE), "KSPSetInitialGuessNonzero");
  return ksp;
}

void set_stop_test(KSP ksp, const SoilOperator& op, PetscStopTest& stop) {
  stop.op = &op;
  petsc_check(KSPConvergedDefaultCreate(&stop.default_test), "KSPConvergedDefaultCreate");
  petsc_check(KSPSetConvergenceTest(ksp, converged_or_stopped, &stop,
                                    [](void* context) {
                                      return KSPConvergedDefaultDestroy(
                                          static_cast<PetscStopTest*>(context)->default_test);
                                    }),
              "KSPSetConvergenceTest");
}

Eigen::VectorXd solve_static(KSP ksp, Vec x, Vec b, PetscStopTest& stop, const Eigen::VectorXd& f,
                             Eigen::VectorXd& last, int& iterations, const char* method) {
  Eigen::VectorXd rhs = f;
  for (Eigen::Index k = 0; k < rhs.size(); ++k)
    if (stop.op->fixed()[k / 3]) rhs[k] = 0.0;
  if (rhs.isZero(0.0)) {  // no load on a free DOF: at rest
    iterations = 0;
    last.setZero();
    return last;
  }
  Eigen::VectorXd u = last;
  petsc_check(VecPlaceArray(b, rhs.data()), "VecPlaceArray");
  petsc_check(VecPlaceArray(x, u.data()), "VecPlaceArray");
  const PetscErrorCode code = KSPSolve(ksp, b, x);
  VecResetArray(x);
  VecResetArray(b);
  if (stop.stopped) std::rethrow_exception(std::exchange(stop.stopped, nullptr));
  petsc_check(code, "KSPSolve");
  PetscInt its = 0;
  KSPConvergedReason reason = KSP_CONVERGED_ITERATING;
  KSPGetIterationNumber(ksp, &its);
  KSPGetConvergedReason(ksp, &reason);
  iterations = static_cast<int>(its);
  if (reason < 0 || !u.allFinite()) {
    PetscReal residual = 0.0;
    KSPGetResidualNorm(ksp, &residual);
    std::ostringstream m;
    m << "fem: the static solve (" << method << ") did not converge in " << iterations
      << " iterations (" << KSPConvergedReasons[reason] << ", residual " << residual / rhs.norm()
      << " of the load)";
    throw std::runtime_error(m.str());
  }
  last = u;
  return u;
}

PetscErrorCode held_stepped_product(const SoilOperator& op, Vec x, Vec y, Eigen::VectorXd& in,
                                    Eigen::VectorXd& out) {
  const std::vector<char>& held = op.fixed();
  const PetscScalar* from = nullptr;
  PetscScalar* to = nullptr;
  PetscCall(VecGetArrayRead(x, &from));
  std::copy(from, from + in.size(), in.data());
  for (Eigen::Index k = 0; k < in.size(); ++k)
    if (held[k / 3]) in[k] = 0.0;
  try {
    op.stepped_stiffness_times(in, out, true);
  } catch (...) {
    VecRestoreArrayRead(x, &from);
    return PETSC_ERR_LIB;
  }
  for (Eigen::Index k = 0; k < in.size(); ++k)
    if (held[k / 3]) out[k] = from[k];
  PetscCall(VecRestoreArrayRead(x, &from));
  PetscCall(VecGetArray(y, &to));
  std::copy(out.data(), out.data() + out.size(), to);
  PetscCall(VecRestoreArray(y, &to));
  return 0;
}

PetscErrorCode copy_into(const Eigen::VectorXd& from, Vec d) {
  PetscScalar* out = nullptr;
  PetscCall(VecGetArray(d, &out));
  std::copy(from.data(), from.data() + from.size(), out);
  PetscCall(VecRestoreArray(d, &out));
  return 0;
}

}  // namespace rumble::fem
