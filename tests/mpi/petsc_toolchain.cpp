// The distributed back end's toolchain, before the back end (issue #33; docs/toolchain.md
// section 9): PETSc's conjugate gradients with algebraic multigrid (GAMG) solve a 3D Poisson
// problem (7-point Laplacian on an n^3 grid, u = 0 beyond it, f = 1) distributed over the ranks
// of mpirun, and on rank 0 alone; the two solutions must agree to 1e-9 relative with
// rtol 1e-12 (an iterative solve is not bit-identical across rank counts, so results that must
// agree across ranks are solved tightly), and multigrid must take far fewer iterations than the
// grid's size (plain CG takes about n x 3). Prints the versions and the iteration counts.
// usage: mpirun -n N petsc_toolchain [n]   (exit code 0: agreed; 1: did not; 2: PETSc failed)
#include <petscksp.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

namespace {

// PETSc's error codes as an exit: every call below is checked (PetscCall needs a function that
// returns PetscErrorCode).
#define CHECK(call)                                                                              \
  do {                                                                                           \
    const PetscErrorCode code_ = (call);                                                         \
    if (code_ != 0) {                                                                            \
      std::fprintf(stderr, "petsc_toolchain: %s failed (%d)\n", #call, static_cast<int>(code_)); \
      return code_;                                                                              \
    }                                                                                            \
  } while (0)

// The 7-point Laplacian of an n^3 grid (spacing 1) on `comm`, its rows split by PETSc.
PetscErrorCode laplacian(MPI_Comm comm, PetscInt n, Mat* A) {
  const PetscInt size = n * n * n;
  CHECK(MatCreateAIJ(comm, PETSC_DECIDE, PETSC_DECIDE, size, size, 7, nullptr, 3, nullptr, A));
  PetscInt first = 0, end = 0;
  CHECK(MatGetOwnershipRange(*A, &first, &end));
  for (PetscInt row = first; row < end; ++row) {
    const PetscInt i = row % n, j = (row / n) % n, k = row / (n * n);
    PetscInt columns[7];
    PetscScalar values[7];
    int count = 0;
    const auto add = [&](PetscInt column, PetscScalar value) {
      columns[count] = column;
      values[count++] = value;
    };
    add(row, 6.0);
    if (i > 0) add(row - 1, -1.0);
    if (i < n - 1) add(row + 1, -1.0);
    if (j > 0) add(row - n, -1.0);
    if (j < n - 1) add(row + n, -1.0);
    if (k > 0) add(row - n * n, -1.0);
    if (k < n - 1) add(row + n * n, -1.0);
    CHECK(MatSetValues(*A, 1, &row, count, columns, values, INSERT_VALUES));
  }
  CHECK(MatAssemblyBegin(*A, MAT_FINAL_ASSEMBLY));
  CHECK(MatAssemblyEnd(*A, MAT_FINAL_ASSEMBLY));
  return 0;
}

// Solves A u = 1 with CG + GAMG on `comm`; the iterations in *its, u gathered whole on rank 0
// of `comm` in *whole.
PetscErrorCode solve(MPI_Comm comm, PetscInt n, PetscInt* its, std::vector<double>* whole) {
  Mat A;
  Vec u, f;
  KSP ksp;
  PC pc;
  CHECK(laplacian(comm, n, &A));
  CHECK(MatCreateVecs(A, &u, &f));
  CHECK(VecSet(f, 1.0));
  CHECK(KSPCreate(comm, &ksp));
  CHECK(KSPSetOperators(ksp, A, A));
  CHECK(KSPSetType(ksp, KSPCG));
  CHECK(KSPGetPC(ksp, &pc));
  CHECK(PCSetType(pc, PCGAMG));
  CHECK(KSPSetTolerances(ksp, 1e-12, PETSC_DEFAULT, PETSC_DEFAULT, 500));
  CHECK(KSPSolve(ksp, f, u));
  KSPConvergedReason reason;
  CHECK(KSPGetConvergedReason(ksp, &reason));
  if (reason <= 0) {
    std::fprintf(stderr, "petsc_toolchain: CG + GAMG did not converge (reason %d)\n",
                 static_cast<int>(reason));
    return PETSC_ERR_NOT_CONVERGED;
  }
  CHECK(KSPGetIterationNumber(ksp, its));
  VecScatter to_zero;
  Vec gathered;
  CHECK(VecScatterCreateToZero(u, &to_zero, &gathered));
  CHECK(VecScatterBegin(to_zero, u, gathered, INSERT_VALUES, SCATTER_FORWARD));
  CHECK(VecScatterEnd(to_zero, u, gathered, INSERT_VALUES, SCATTER_FORWARD));
  PetscInt local = 0;
  CHECK(VecGetLocalSize(gathered, &local));
  const PetscScalar* values = nullptr;
  CHECK(VecGetArrayRead(gathered, &values));
  whole->assign(values, values + local);
  CHECK(VecRestoreArrayRead(gathered, &values));
  CHECK(VecScatterDestroy(&to_zero));
  CHECK(VecDestroy(&gathered));
  CHECK(KSPDestroy(&ksp));
  CHECK(VecDestroy(&u));
  CHECK(VecDestroy(&f));
  CHECK(MatDestroy(&A));
  return 0;
}

// 0 when the distributed solution agrees with rank 0's own; prints what was found.
int compare(PetscInt n, int ranks, PetscInt its_world, PetscInt its_self,
            const std::vector<double>& world, const std::vector<double>& self) {
  double difference = 0.0, norm = 0.0;
  for (std::size_t k = 0; k < self.size(); ++k) {
    difference += (world[k] - self[k]) * (world[k] - self[k]);
    norm += self[k] * self[k];
  }
  const double relative = std::sqrt(difference / norm);
  std::printf(
      "PETSc %d.%d.%d, %d rank(s): %d^3 Poisson, CG + GAMG %d iterations (rank 0 alone "
      "%d); solutions differ by %.2e relative\n",
      PETSC_VERSION_MAJOR, PETSC_VERSION_MINOR, PETSC_VERSION_SUBMINOR, ranks, static_cast<int>(n),
      static_cast<int>(its_world), static_cast<int>(its_self), relative);
  const bool agree = world.size() == self.size() && relative < 1e-9;
  const bool multigrid = its_world < n && its_self < n;  // plain CG: about 3 n
  if (!agree) std::fprintf(stderr, "petsc_toolchain: the solutions differ\n");
  if (!multigrid) std::fprintf(stderr, "petsc_toolchain: GAMG did not cut the iterations\n");
  return agree && multigrid ? 0 : 1;
}

int run(PetscInt n) {
  int rank = 0, ranks = 1;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  MPI_Comm_size(PETSC_COMM_WORLD, &ranks);
  PetscInt its_world = 0, its_self = 0;
  std::vector<double> world, self;
  if (solve(PETSC_COMM_WORLD, n, &its_world, &world) != 0) return 2;
  if (rank != 0) return 0;
  if (solve(PETSC_COMM_SELF, n, &its_self, &self) != 0) return 2;
  return compare(n, ranks, its_world, its_self, world, self);
}

}  // namespace

int main(int argc, char** argv) {
  if (PetscInitialize(&argc, &argv, nullptr, nullptr) != 0) return 2;
  const PetscInt n = argc > 1 ? std::atoi(argv[1]) : 24;
  int status = run(n);
  MPI_Allreduce(MPI_IN_PLACE, &status, 1, MPI_INT, MPI_MAX, PETSC_COMM_WORLD);
  PetscFinalize();
  return status;
}
