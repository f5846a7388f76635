#include "statics/petsc_static_solver.hpp"

#include <petscksp.h>

#include <algorithm>
#include <chrono>
#include <stdexcept>
#include <type_traits>
#include <vector>

#include "operator/effective_matrix.hpp"
#include "statics/petsc_cg.hpp"
#include "statics/petsc_session.hpp"

namespace rumble::fem {

// PETSc's matrix shares the rows' arrays (no copy of K + S, a few hundred MB at 1e6 DOFs).
static_assert(std::is_same_v<PetscInt, RowSparse::StorageIndex>,
              "PETSc's indices must be the rows' (a 32-bit PETSc, as Debian ships it)");
static_assert(std::is_same_v<PetscScalar, double>, "a real, double PETSc");

namespace {

/// K + S in 3 x 3 blocks, each column-major as BAIJ stores them, compressed block rows (node
/// rows; within a block, entries absent from the rows are zero): a block row is then one
/// column-oriented MatSetValuesBlocked. (PETSc 3.18 takes no such arrays without a copy for
/// blocks larger than 1: MatCreateSeqBAIJWithArrays refuses them.)
struct PetscBlockRows {
  std::vector<PetscInt> start, column;
  std::vector<PetscScalar> value;
};

/// a in blocks; the matrix must have 3 x 3 blocks' rows (3 DOFs per node).
PetscBlockRows block_rows(const RowSparse& a) {
  PetscBlockRows b;
  const Eigen::Index nodes = a.rows() / 3;
  b.start.assign(nodes + 1, 0);
  const auto blocks = static_cast<std::size_t>(a.nonZeros() / 9 + nodes);  // (9 a full block)
  b.column.reserve(blocks);
  b.value.reserve(9 * blocks);
  std::vector<PetscInt> slot(nodes, -1);  // per node column: its block in the current row
  for (Eigen::Index i = 0; i < nodes; ++i) {
    const auto first = static_cast<PetscInt>(b.column.size());
    for (int c = 0; c < 3; ++c)
      for (RowSparse::InnerIterator e(a, 3 * i + c); e; ++e) {
        const PetscInt node = e.col() / 3;
        if (slot[node] < first) {  // (a block of an earlier row, or none yet)
          slot[node] = static_cast<PetscInt>(b.column.size());
          b.column.push_back(node);
        }
      }
    std::sort(b.column.begin() + first, b.column.end());
    for (auto k = static_cast<std::size_t>(first); k < b.column.size(); ++k)
      slot[b.column[k]] = static_cast<PetscInt>(k);
    b.value.resize(9 * b.column.size(), 0.0);
    for (int c = 0; c < 3; ++c)
      for (RowSparse::InnerIterator e(a, 3 * i + c); e; ++e)
        b.value[9 * slot[e.col() / 3] + 3 * (e.col() % 3) + c] = e.value();
    b.start[i + 1] = static_cast<PetscInt>(b.column.size());
  }
  return b;
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
  RowSparse rows;                        // K + S, whose arrays aij shares
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
  p.rows = full_combination(op, {.stiffness = 1.0, .springs = true});
  p.rows.makeCompressed();
  const auto n = static_cast<PetscInt>(p.rows.rows());
  petsc_check(MatCreateSeqAIJWithArrays(PETSC_COMM_SELF, n, n, p.rows.outerIndexPtr(),
                                        p.rows.innerIndexPtr(), p.rows.valuePtr(), &p.aij),
              "MatCreateSeqAIJWithArrays");
  petsc_check(MatSetBlockSize(p.aij, 3), "MatSetBlockSize");  // nodes, for GAMG's aggregates
  petsc_check(MatSetOption(p.aij, MAT_SPD, PETSC_TRUE), "MatSetOption");
  make_product(storage);
  petsc_check(VecCreateSeqWithArray(PETSC_COMM_SELF, 3, n, nullptr, &p.x), "VecCreateSeqWithArray");
  petsc_check(VecCreateSeqWithArray(PETSC_COMM_SELF, 3, n, nullptr, &p.b), "VecCreateSeqWithArray");
  build_solver(nodes);
  setup_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  last_ = Eigen::VectorXd::Zero(n);
}

void PetscStaticSolver::make_product(Storage storage) {
  Petsc& p = *petsc_;
  const auto n = static_cast<PetscInt>(p.rows.rows());
  if (storage == Storage::kSteppedProduct) {
    p.in.resize(n);
    p.out.resize(n);
    petsc_check(MatCreateShell(PETSC_COMM_SELF, n, n, n, n, &p, &p.product), "MatCreateShell");
    petsc_check(MatShellSetOperation(p.product, MATOP_MULT,
                                     reinterpret_cast<void (*)(void)>(&Petsc::stepped_product)),
                "MatShellSetOperation");
    petsc_check(MatSetBlockSize(p.product, 3), "MatSetBlockSize");
  } else if (storage == Storage::kBaijProduct) {
    const PetscBlockRows blocks = block_rows(p.rows);
    petsc_check(MatCreate(PETSC_COMM_SELF, &p.product), "MatCreate");
    petsc_check(MatSetSizes(p.product, n, n, n, n), "MatSetSizes");
    petsc_check(MatSetType(p.product, MATSEQBAIJ), "MatSetType");
    petsc_check(MatSetOption(p.product, MAT_ROW_ORIENTED, PETSC_FALSE), "MatSetOption");
    petsc_check(MatSeqBAIJSetPreallocationCSR(p.product, 3, blocks.start.data(),
                                              blocks.column.data(), blocks.value.data()),
                "MatSeqBAIJSetPreallocationCSR");
    petsc_check(MatSetOption(p.product, MAT_SPD, PETSC_TRUE), "MatSetOption");
  }
}

PetscStaticSolver::~PetscStaticSolver() = default;

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
  if (p.product) petsc_check(PCSetUseAmat(pc, PETSC_TRUE), "PCSetUseAmat");  // the mesh's level
  petsc_check(KSPSetFromOptions(p.ksp), "KSPSetFromOptions");
  set_stop_test(p.ksp, op_, p.stop);
  petsc_check(KSPSetUp(p.ksp), "KSPSetUp (GAMG's hierarchy)");
  PetscInt levels = 0;
  petsc_check(PCMGGetLevels(pc, &levels), "PCMGGetLevels");
  levels_ = static_cast<int>(levels);
}

Eigen::VectorXd PetscStaticSolver::solve(const Eigen::VectorXd& f) {
  Petsc& p = *petsc_;
  return solve_static(p.ksp, p.x, p.b, p.stop, f, last_, iterations_, "CG with PETSc's GAMG");
}

}  // namespace rumble::fem
