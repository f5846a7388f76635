#include "statics/petsc_stop_test.hpp"

#include "statics/petsc_session.hpp"

namespace rumble::fem {

namespace {

PetscErrorCode converged_or_stopped(KSP ksp, PetscInt it, PetscReal rnorm,
                                    KSPConvergedReason* reason, void* context) {
  auto* test = static_cast<PetscStopTest*>(context);
  try {
    test->op->check_stop();
  } catch (...) {
    test->stopped = std::current_exception();
    *reason = KSP_DIVERGED_ITS;
    return 0;
  }
  return KSPConvergedDefault(ksp, it, rnorm, reason, test->default_test);
}

}  // namespace

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

}  // namespace rumble::fem
