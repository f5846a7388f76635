// What the FEM soil costs in memory, as measured (docs/fem-soil.md section 7.2 has the
// measurements and the commands): the model behind its two estimates of a run's peak resident
// memory, before meshing from the estimated DOFs (mesh/mesh_memory.hpp: a mesh that cannot run
// is refused then) and after the assembly from the matrix itself (size(), which the host writes
// beside what it measured). Every size is estimated before it is spent.
#pragma once

#include <algorithm>
#include <cmath>

namespace rumble::fem::memory {

/// DOFs up to which the statics factor K + S (CHOLMOD); above, PETSc's CG with a multigrid
/// (statics/static_solver.hpp).
inline constexpr double kFactorLimitDofs = 4e5;

/// The process without the soil [bytes]: the engine, its plugins and their libraries (gmsh,
/// PETSc, OpenMPI); 60-90 MB measured with the smallest meshes.
inline constexpr double kProcessBytes = 1.0e8;

/// What the soil holds from its assembly into the statics, per DOF [bytes]: K in compressed rows
/// with its node graph (about 42 nonzeros per row, 12 B each), K's upper blocks in float, the
/// mesh, the lumped mass, the state and its scratch vectors (780 B per DOF at 1.0e6 DOFs).
inline constexpr double kHeldBytesPerDof = 800.0;

/// L's nonzeros of the factor of K + S for n DOFs: 4.7 n^1.45, fitted to the stiff example's
/// graded hemispheres (5.7e6, 9.8e7, 3.9e8 at 1.7e4, 1.1e5, 2.9e5 DOFs; within 8 %).
inline double factor_nonzeros(double dofs) {
  return 4.7 * std::pow(dofs, 1.45);
}

/// CHOLMOD's peak while it factors [bytes per nonzero of L]: its supernodal L and workspace
/// (its own count, memory_usage: 10.9-12.9 B at those three sizes), and the lower triangle it
/// is given.
inline constexpr double kFactorBytesPerNonzero = 11.5;

/// The implicit step's factor on one of `ranks` ranks at its peak, beyond what the rank holds
/// for its explicit steps [bytes] (MUMPS's Cholesky through PETSc, distributed/
/// rank_effective_system.hpp): 17.5 B per nonzero of the rank's even share of the whole factor
/// (factor_nonzeros: one process's count) and 15 MB (MUMPS's libraries and buffers), which
/// includes PETSc's matrix of K_eff. Fitted to fem_small.json's hemisphere on 2 ranks
/// (docs/fem-soil.md §8, "The implicit scheme on the ranks": 77-83, 418-489 and 1533-1568 MB per
/// rank at 1.9e4, 6.8e4 and 1.7e5 DOFs; CHOLMOD's 11.5 B per nonzero on one process).
inline constexpr double kRankFactorBytesPerNonzero = 17.5;
inline constexpr double kRankFactorBytes = 15e6;
inline double rank_factor_bytes(double whole_dofs, int ranks) {
  return kRankFactorBytesPerNonzero * factor_nonzeros(whole_dofs) / ranks + kRankFactorBytes;
}

/// PETSc's GAMG on one process (statics.solver gamg or auto without mesh.refine) at its peak,
/// beyond what the soil holds into the statics, per nonzero of K [bytes]: its matrix is K's own
/// rows with the springs added in place (no copy), so this is the plain aggregation's graph,
/// prolongators and Galerkin products (formed by the "scalable" algorithm, petsc_session.cpp)
/// and CG's and the smoothers' vectors: 8.7 B measured on a Kuhn box of 2.1e5 DOFs
/// (tests/fem/gamg_statics_test.cpp) and 388 B per DOF on the stiff example at 8.8e5 DOFs
/// (docs/fem-soil.md §7.2). One smoothing of the prolongator would take 15.4 B.
inline constexpr double kGamgProcessBytesPerNonzero = 8.7;

/// PETSc's GAMG on many ranks at its peak, beyond what a rank holds after its layout, per nonzero
/// of the rank's part of K [bytes]: its matrix (AIJ, 12 B per nonzero), the plain aggregation's
/// prolongators and Galerkin products, each product's intermediates freed once it is formed,
/// less the part's own rows (about 12 B per nonzero), freed once PETSc's matrix holds them
/// (distributed/distributed_statics.cpp). Fitted to the stiff example on 2 ranks (docs/fem-soil.md
/// §8: 0.95-0.99 GB per rank at the statics at 1.0e6 DOFs, 1.26-1.29 GB while the rows were
/// kept, when this was 28 B; the estimate 1.03 of the peak there, 0.99 refined once at 9.3e5
/// DOFs); one smoothing of the prolongator
/// (PETSC_OPTIONS -fem_statics_pc_gamg_agg_nsmooths 1) needs about 27 B more.
inline constexpr double kGamgBytesPerNonzero = 18.0;

/// The geometric multigrid (statics.solver geometric, mesh.refine 1) at its peak, beyond what the
/// soil holds into the statics, per nonzero of K [bytes]: it frees K's rows first (12 B per
/// nonzero and their node graph), then adds the coarse level (K + S of gmsh's mesh and the
/// interpolation) and PETSc's GAMG on it with CG's and the V-cycle's vectors on the mesh: less
/// than it freed, so the build's peak stays the run's. Measured on the stiff example at 9.3e5
/// DOFs (docs/fem-soil.md §7.1): 813 MB resident at the start, 321 MB with the rows freed, 428
/// MB with the coarse level, 721 MB after the first solve: -92 MB over about 4.2e7 nonzeros.
inline constexpr double kGeometricBytesPerNonzero = -2.2;

/// The geometric multigrid on many ranks (statics.solver geometric under mpirun, mesh.refine 1)
/// at its peak, beyond what a rank holds after its layout, per nonzero of the rank's part of K
/// [bytes]: the coarse part's operator and its MPIAIJ K + S (1/8 of the part's), GAMG's
/// hierarchy on it, the interpolation, the fine level's diagonal and the CG, smoother and shell
/// vectors (distributed/geometric_rank_statics.hpp), less the part's rows in double (12 B per
/// nonzero), freed before the set-up: the fine product forms K from the tetrahedra. Fitted to
/// the stiff example refined once, 9.33e5 DOFs on 2 ranks (docs/fem-soil.md §8, "K without its
/// rows": 0.53-0.55 GB per rank at the statics; 15 B and 0.77-0.80 GB while the rows were kept).
inline constexpr double kGeometricRankBytesPerNonzero = 3.0;

/// The aggregation multigrid on many ranks (statics.solver aggregation, or auto without
/// mesh.refine) at its peak, beyond what a rank holds after its layout, per nonzero of the rank's
/// part of K [bytes]: the mesh's node graph while the aggregates are made, the prolongator (18
/// nonzeros per node), the coarse level's MPIAIJ matrix (six DOFs per aggregate) and GAMG's
/// hierarchy on it, the fine level's diagonal and the CG, smoother and shell vectors
/// (distributed/aggregation_rank_statics.hpp), less the part's rows in double (12 B per
/// nonzero), freed before the set-up: about what it adds. Fitted to the stiff example at 1.0e6
/// DOFs on 2 ranks (docs/fem-soil.md §8, "The statics on the ranks without an assembled
/// matrix"): rank 0 held about 0.602 GB after its layout (GAMG's estimate on the same split, less
/// its 18 B per nonzero) and peaked at 0.595 GB in these statics, -0.3 B per nonzero; 0 taken.
inline constexpr double kAggregationRankBytesPerNonzero = 0.0;

/// The whole mesh's nodes and tetrahedra as rank 0 keeps them on many ranks, per DOF [bytes]:
/// 24 B per node and 16 B per tetrahedron, about 5.5 tetrahedra per node (docs/fem-soil.md §8,
/// "What rank 0 keeps").
inline constexpr double kMeshBytesPerDof = 40.0;

/// Rank 0's peak while it meshes the whole mesh and splits it over N ranks, before any rank builds
/// its share, per DOF of that mesh [bytes] (docs/fem-soil.md §8, "Planning the ranks"): gmsh's
/// meshing, 540 B; the split (the whole mesh as a DMPlex, what travels with each of its points,
/// PT-Scotch's graph, and rank 0's part received back) 352 B + 228 B / N. Measured on the stiff
/// example at 1.0e6 DOFs (release, 2026-12-07): meshed by gmsh on 4 ranks 540 B; from the mesh
/// cache 466 and 428 B on 2 and 3 ranks (the split's), 436 B on 4 (the cache's read).
inline constexpr double kRootMeshingBytesPerDof = 540.0;
inline constexpr double kRootSplitBytesPerDof = 352.0;
inline constexpr double kRootSplitPartBytesPerDof = 228.0;  // (divided by N)

/// Rank 0's peak through the meshing and the split of a mesh of `dofs` over `ranks` [bytes].
inline double root_split_bytes(double dofs, int ranks) {
  return kProcessBytes + dofs * std::max(kRootMeshingBytesPerDof,
                                         kRootSplitBytesPerDof + kRootSplitPartBytesPerDof / ranks);
}

/// Nonzeros of K per DOF on the meshes measured (about 14 neighbours per node, 3 x 3 blocks).
inline constexpr double kNonzerosPerDof = 45.0;

/// What factoring K + S adds at its peak [bytes], for n DOFs.
inline double factor_bytes(double dofs) {
  return kFactorBytesPerNonzero * factor_nonzeros(dofs);
}

/// What GAMG's set-up on one process adds at its peak to what the soil holds [bytes], for K's
/// nonzeros.
inline double gamg_bytes(double nonzeros) {
  return kGamgProcessBytesPerNonzero * nonzeros;
}

/// What the first static solve adds to what the soil holds [bytes], by its path, for n DOFs and
/// K's nonzeros (geometric: statics.solver geometric's, negative: it frees more than it adds).
inline double statics_bytes(double dofs, double nonzeros, bool geometric = false) {
  if (dofs <= kFactorLimitDofs) return factor_bytes(dofs);
  return geometric ? kGeometricBytesPerNonzero * nonzeros : gamg_bytes(nonzeros);
}

/// A run's peak resident memory for a mesh of n DOFs [bytes], before meshing: the process, what
/// the soil holds, and the statics' peak on top of it (the steps need less: the statics' factor
/// or hierarchy and K's compressed rows are freed before them).
inline double run_peak_bytes(double dofs) {
  return kProcessBytes + kHeldBytesPerDof * dofs + statics_bytes(dofs, kNonzerosPerDof * dofs);
}

}  // namespace rumble::fem::memory
