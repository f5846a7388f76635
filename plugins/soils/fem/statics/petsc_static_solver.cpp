#include "statics/petsc_static_solver.hpp"

#include <petscksp.h>

#include <chrono>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <type_traits>
#include <utility>
#include <vector>

#include "operator/effective_matrix.hpp"
#include "statics/petsc_cg.hpp"
#include "statics/petsc_session.hpp"

namespace rumble::fem {

// PETSc's matrix shares K's arrays (no copy of K + S, 0.5 GB at 1e6 DOFs).
static_assert(std::is_same_v<PetscInt, std::int32_t>,
              "PETSc's indices must be K's column indices (a 32-bit PETSc, as Debian ships it)");
static_assert(std::is_same_v<PetscScalar, double>, "a real, double PETSc");

namespace {

/// K's rows (the operator's, handed over) turned into K + S in place: the entries
/// full_combination(op, {.stiffness = 1, .springs = true}) gives (operator/effective_matrix.hpp),
/// to the bit and with its pattern: the boundary's blocks added on the diagonal, a held node's
/// rows its diagonal 1 alone and its columns left out, compacted towards the front. (Kept as
/// stored zeros, they tied held nodes to their neighbours in GAMG's aggregates: held DOFs came
/// out 1e-16, not 0, tests/fem/gamg_statics_test.cpp.)
void add_springs_and_hold(CsrMatrix::Rows& k, const SoilOperator& op) {
  const std::vector<double> block = boundary_blocks(op, {.stiffness = 1.0, .springs = true});
  const auto& held = op.fixed();
  const auto rows = static_cast<std::int64_t>(k.start.size()) - 1;
  std::int64_t kept = 0;  // (entries written so far: never ahead of the one read)
  for (std::int64_t row = 0; row < rows; ++row) {
    const std::int64_t node = row / 3, first = k.start[row], last = k.start[row + 1];
    k.start[row] = kept;
    if (held[node]) {
      k.column[kept] = static_cast<std::int32_t>(row);
      k.value[kept++] = 1.0;
      continue;
    }
    for (std::int64_t e = first; e < last; ++e) {
      const std::int64_t col = k.column[e];
      if (held[col / 3]) continue;
      double value = k.value[e];
      if (col / 3 == node) value += block[9 * node + 3 * (row % 3) + col % 3];
      k.column[kept] = static_cast<std::int32_t>(col);
      k.value[kept++] = value;
    }
  }
  k.start[rows] = kept;
  k.column.resize(static_cast<std::size_t>(kept));  // (no reallocation: the memory stays K's)
  k.value.resize(static_cast<std::size_t>(kept));
}

}  // namespace

struct PetscStaticSolver::Petsc {
  ~Petsc() {
    // (errors ignored: a destructor; the session outlives these objects, as it is a member)
    KSPDestroy(&ksp);
    VecDestroy(&x);
    VecDestroy(&b);
    MatDestroy(&product);
    MatDestroy(&aij);
  }
  /// y = (K + S) x, fixed DOFs as identity as in aij (petsc_cg.hpp): a MATSHELL's MATOP_MULT.
  static PetscErrorCode stepped_product(Mat a, Vec x, Vec y) {
    Petsc* p = nullptr;
    PetscCall(MatShellGetContext(a, &p));
    return held_stepped_product(*p->op, x, y, p->in, p->out);
  }
  std::shared_ptr<PetscSession> session = PetscSession::get();
  const SoilOperator* op = nullptr;
  std::vector<PetscInt> row_start;  // K + S's rows: K's own arrays, which aij shares
  std::vector<std::int32_t> column;
  std::vector<double> value;
  Mat aij = nullptr, product = nullptr;  // product: CG's and the mesh level's, or null (aij)
  Vec x = nullptr, b = nullptr;          // over the solver's own vectors (VecPlaceArray)
  Eigen::VectorXd in, out;               // stepped_product's
  KSP ksp = nullptr;
  PetscStopTest stop;
};

PetscStaticSolver::PetscStaticSolver(const SoilOperator& op, const Eigen::Matrix3Xd& nodes,
                                     Storage storage)
    : op_(op), petsc_(std::make_unique<Petsc>()) {
  const auto start = std::chrono::steady_clock::now();
  Petsc& p = *petsc_;
  p.op = &op;
  take_rows(op);
  const auto n = static_cast<PetscInt>(p.row_start.size() - 1);
  petsc_check(MatCreateSeqAIJWithArrays(PETSC_COMM_SELF, n, n, p.row_start.data(), p.column.data(),
                                        p.value.data(), &p.aij),
              "MatCreateSeqAIJWithArrays");
  petsc_check(MatSetBlockSize(p.aij, 3), "MatSetBlockSize");  // nodes, for GAMG's aggregates
  petsc_check(MatSetOption(p.aij, MAT_SPD, PETSC_TRUE), "MatSetOption");
  if (storage == Storage::kSteppedProduct) make_stepped_product();
  petsc_check(VecCreateSeqWithArray(PETSC_COMM_SELF, 3, n, nullptr, &p.x), "VecCreateSeqWithArray");
  petsc_check(VecCreateSeqWithArray(PETSC_COMM_SELF, 3, n, nullptr, &p.b), "VecCreateSeqWithArray");
  build_solver(nodes);
  setup_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  last_ = Eigen::VectorXd::Zero(n);
}

void PetscStaticSolver::take_rows(const SoilOperator& op) {
  Petsc& p = *petsc_;
  CsrMatrix::Rows k = op.take_stiffness().release_rows();
  if (k.column.size() > static_cast<std::size_t>(std::numeric_limits<PetscInt>::max()))
    throw std::length_error("fem: the stiffness has too many nonzeros for PETSc's 32-bit indices");
  add_springs_and_hold(k, op);
  p.row_start.assign(k.start.begin(), k.start.end());
  std::vector<std::int64_t>().swap(k.start);
  p.column = std::move(k.column);
  p.value = std::move(k.value);
}

void PetscStaticSolver::make_stepped_product() {
  Petsc& p = *petsc_;
  const auto n = static_cast<PetscInt>(p.row_start.size() - 1);
  p.in.resize(n);
  p.out.resize(n);
  petsc_check(MatCreateShell(PETSC_COMM_SELF, n, n, n, n, &p, &p.product), "MatCreateShell");
  petsc_check(MatShellSetOperation(p.product, MATOP_MULT,
                                   reinterpret_cast<void (*)(void)>(&Petsc::stepped_product)),
              "MatShellSetOperation");
  petsc_check(MatSetBlockSize(p.product, 3), "MatSetBlockSize");
}

PetscStaticSolver::~PetscStaticSolver() = default;

std::size_t PetscStaticSolver::bytes() const {
  const Petsc& p = *petsc_;
  return p.row_start.capacity() * sizeof(PetscInt) + p.column.capacity() * 4 +
         p.value.capacity() * 8;
}

void PetscStaticSolver::build_solver(const Eigen::Matrix3Xd& nodes) {
  Petsc& p = *petsc_;
  // The rigid-body modes from the coordinates: 3 translations, 3 rotations, orthonormalised.
  Vec coordinates = nullptr;
  MatNullSpace modes = nullptr;
  // (PETSc reads the coordinates only)
  petsc_check(VecCreateSeqWithArray(PETSC_COMM_SELF, 3, static_cast<PetscInt>(nodes.size()),
                                    const_cast<double*>(nodes.data()), &coordinates),
              "VecCreateSeqWithArray");
  petsc_check(MatNullSpaceCreateRigidBody(coordinates, &modes), "MatNullSpaceCreateRigidBody");
  petsc_check(MatSetNearNullSpace(p.aij, modes), "MatSetNearNullSpace");
  if (p.product) petsc_check(MatSetNearNullSpace(p.product, modes), "MatSetNearNullSpace");
  MatNullSpaceDestroy(&modes);  // (the matrices hold it)
  VecDestroy(&coordinates);

  PC pc = nullptr;
  p.ksp = static_cg(PETSC_COMM_SELF, p.product ? p.product : p.aij, p.aij, kTolerance);
  petsc_check(KSPGetPC(p.ksp, &pc), "KSPGetPC");
  petsc_check(PCSetType(pc, PCGAMG), "PCSetType");
  // Plain aggregation: the prolongator not smoothed. On the stiff example at 8.8e5 DOFs the
  // static start (set-up and 4 solves) took 27-28 s with 1288 B per DOF at its peak, against
  // 40-41 s and 1677 B with PETSc's one smoothing (its denser prolongator and coarse levels);
  // 78 CG iterations for the first solve, against 24 (docs/fem-soil.md §7.1).
  petsc_check(PCGAMGSetNSmooths(pc, 0), "PCGAMGSetNSmooths");
  if (p.product) petsc_check(PCSetUseAmat(pc, PETSC_TRUE), "PCSetUseAmat");  // the mesh's level
  petsc_check(KSPSetFromOptions(p.ksp), "KSPSetFromOptions");
  set_stop_test(p.ksp, op_, p.stop);
  {
    const ScopedPetscOption clear(kClearProducts, "true");
    petsc_check(KSPSetUp(p.ksp), "KSPSetUp (GAMG's hierarchy)");
  }
  PetscInt levels = 0;
  petsc_check(PCMGGetLevels(pc, &levels), "PCMGGetLevels");
  levels_ = static_cast<int>(levels);
}

Eigen::VectorXd PetscStaticSolver::solve(const Eigen::VectorXd& f) {
  Petsc& p = *petsc_;
  return solve_static(p.ksp, p.x, p.b, p.stop, f, last_, iterations_, "CG with PETSc's GAMG");
}

}  // namespace rumble::fem
