// The statics' two-level geometric multigrid as a PETSc preconditioner (docs/fem-soil.md §7.1),
// set up alike on one process (geometric_static_solver.hpp) and on the ranks
// (distributed/geometric_rank_statics.hpp): the fine level smoothed by Chebyshev(2) with Jacobi
// (the fine matrix's MATOP_GET_DIAGONAL; the spectrum's bound from 10 CG iterations, [0.1, 1.1]
// times the largest eigenvalue of D^-1 A, GAMG's levels' defaults), the coarse level solved by
// one V-cycle of GAMG (a fixed linear operator, as CG needs), the interpolation given, its
// transpose the restriction. Included by those solvers' .cpp files only (no header of the room
// includes PETSc's).
#pragma once

#include <petscksp.h>

namespace rumble::fem {

/// Makes ksp's preconditioner the two-level multigrid on `fine` (the operator ksp solves),
/// `coarse` and `interpolation` (coarse to fine). The caller then sets ksp up. Throws
/// std::runtime_error when PETSc fails.
void set_two_level_multigrid(KSP ksp, Mat fine, Mat coarse, Mat interpolation);

/// The levels of ksp's multigrid once set up: the fine one and GAMG's on the coarse matrix.
/// Throws std::runtime_error when PETSc fails.
int two_level_multigrid_levels(KSP ksp);

}  // namespace rumble::fem
