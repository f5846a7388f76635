#include "statics/two_level_multigrid.hpp"

#include "statics/petsc_session.hpp"

namespace rumble::fem {

void set_two_level_multigrid(KSP ksp, Mat fine, Mat coarse, Mat interpolation) {
  PC pc = nullptr;
  petsc_check(KSPGetPC(ksp, &pc), "KSPGetPC");
  petsc_check(PCSetType(pc, PCMG), "PCSetType");
  petsc_check(PCMGSetLevels(pc, 2, nullptr), "PCMGSetLevels");
  petsc_check(PCMGSetType(pc, PC_MG_MULTIPLICATIVE), "PCMGSetType");
  petsc_check(PCMGSetGalerkin(pc, PC_MG_GALERKIN_NONE), "PCMGSetGalerkin");
  petsc_check(PCMGSetInterpolation(pc, 1, interpolation), "PCMGSetInterpolation");
  KSP smoother = nullptr, estimate = nullptr;
  PC jacobi = nullptr;
  petsc_check(PCMGGetSmoother(pc, 1, &smoother), "PCMGGetSmoother");
  petsc_check(KSPSetOperators(smoother, fine, fine), "KSPSetOperators");
  petsc_check(KSPSetType(smoother, KSPCHEBYSHEV), "KSPSetType");
  petsc_check(KSPChebyshevEstEigSet(smoother, 0.0, 0.1, 0.0, 1.1), "KSPChebyshevEstEigSet");
  petsc_check(KSPChebyshevEstEigGetKSP(smoother, &estimate), "KSPChebyshevEstEigGetKSP");
  if (estimate) petsc_check(KSPSetType(estimate, KSPCG), "KSPSetType");
  petsc_check(KSPSetTolerances(smoother, PETSC_DEFAULT, PETSC_DEFAULT, PETSC_DEFAULT, 2),
              "KSPSetTolerances");
  petsc_check(KSPGetPC(smoother, &jacobi), "KSPGetPC");
  petsc_check(PCSetType(jacobi, PCJACOBI), "PCSetType");
  KSP coarse_solve = nullptr;
  PC gamg = nullptr;
  petsc_check(PCMGGetCoarseSolve(pc, &coarse_solve), "PCMGGetCoarseSolve");
  petsc_check(KSPSetOperators(coarse_solve, coarse, coarse), "KSPSetOperators");
  petsc_check(KSPSetType(coarse_solve, KSPPREONLY), "KSPSetType");
  petsc_check(KSPGetPC(coarse_solve, &gamg), "KSPGetPC");
  petsc_check(PCSetType(gamg, PCGAMG), "PCSetType");
}

int two_level_multigrid_levels(KSP ksp) {
  PC pc = nullptr, gamg = nullptr;
  KSP coarse_solve = nullptr;
  petsc_check(KSPGetPC(ksp, &pc), "KSPGetPC");
  petsc_check(PCMGGetCoarseSolve(pc, &coarse_solve), "PCMGGetCoarseSolve");
  petsc_check(KSPGetPC(coarse_solve, &gamg), "KSPGetPC");
  PetscInt below = 1;
  PetscBool is_gamg = PETSC_FALSE;  // (PETSC_OPTIONS may choose another coarse solve)
  petsc_check(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(gamg), PCGAMG, &is_gamg),
              "PetscObjectTypeCompare");
  if (is_gamg) petsc_check(PCMGGetLevels(gamg, &below), "PCMGGetLevels");
  return 1 + static_cast<int>(below);
}

}  // namespace rumble::fem
