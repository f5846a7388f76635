#include "statics/geometric_static_solver.hpp"

#include <petscksp.h>

#include <algorithm>
#include <chrono>
#include <stdexcept>
#include <type_traits>
#include <vector>

#include "statics/petsc_cg.hpp"
#include "statics/petsc_session.hpp"
#include "statics/two_level_multigrid.hpp"

namespace rumble::fem {

static_assert(std::is_same_v<PetscInt, RowSparse::StorageIndex>,
              "PETSc's indices must be the rows' (a 32-bit PETSc, as Debian ships it)");

struct GeometricStaticSolver::Petsc {
  ~Petsc() {
    // (errors ignored: a destructor; the session outlives these objects, as it is a member)
    KSPDestroy(&ksp);
    VecDestroy(&x);
    VecDestroy(&b);
    MatDestroy(&interpolation);
    MatDestroy(&node_interpolation);
    MatDestroy(&coarse);
    MatDestroy(&fine);
  }
  /// y = (K + S) x, held DOFs as identity (petsc_cg.hpp): the fine level's MATOP_MULT.
  static PetscErrorCode multiply(Mat a, Vec x, Vec y) {
    Petsc* p = nullptr;
    PetscCall(MatShellGetContext(a, &p));
    return held_stepped_product(*p->op, x, y, p->in, p->out);
  }
  /// The diagonal of K + S (1 on held DOFs): the fine level's MATOP_GET_DIAGONAL, for Jacobi.
  static PetscErrorCode get_diagonal(Mat a, Vec d) {
    Petsc* p = nullptr;
    PetscCall(MatShellGetContext(a, &p));
    return copy_into(p->diagonal, d);
  }
  std::shared_ptr<PetscSession> session = PetscSession::get();
  const SoilOperator* op = nullptr;
  CoarseLevel level;                  // its arrays shared by coarse and node_interpolation
  Eigen::VectorXd diagonal, in, out;  // the shell's
  Mat fine = nullptr, coarse = nullptr;
  Mat node_interpolation = nullptr;  // fine nodes x coarse nodes
  Mat interpolation = nullptr;       // the same on each of a node's 3 DOFs (MAIJ)
  Vec x = nullptr, b = nullptr;      // over the solver's own vectors (VecPlaceArray)
  KSP ksp = nullptr;
  PetscStopTest stop;
};

namespace {

/// The diagonal of K + S (1 on held DOFs).
Eigen::VectorXd stiffness_diagonal(const SoilOperator& op) {
  Eigen::VectorXd d = op.stiffness_diagonal();
  for (const BoundaryNode& b : op.boundary())
    for (int c = 0; c < 3; ++c) d[3 * b.node + c] += b.spring(c, c);
  for (Eigen::Index r = 0; r < d.size(); ++r)
    if (op.fixed()[r / 3]) d[r] = 1.0;
  return d;
}

}  // namespace

GeometricStaticSolver::GeometricStaticSolver(const SoilOperator& op,
                                             const std::function<CoarseLevel()>& coarse)
    : op_(op), petsc_(std::make_unique<Petsc>()) {
  const auto start = std::chrono::steady_clock::now();
  Petsc& p = *petsc_;
  p.op = &op;
  p.diagonal = stiffness_diagonal(op);
  // The rows were read for their diagonal alone: nothing else of the statics needs them
  // (docs/fem-soil.md §7.1), and at 1e6 DOFs they are 0.55 GB, more than the levels take.
  op.release_stiffness();
  p.level = coarse();
  if (p.level.interpolation.rows() != op.nodes() ||
      p.level.interpolation.cols() != p.level.nodes.cols() ||
      p.level.matrix.rows() != 3 * p.level.nodes.cols())
    throw std::invalid_argument(
        "fem: the geometric multigrid's coarse level does not fit the "
        "soil's mesh (its interpolation's or matrix's size)");
  make_levels();
  build_solver();
  setup_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  last_ = Eigen::VectorXd::Zero(op.dofs());
}

GeometricStaticSolver::~GeometricStaticSolver() = default;

std::size_t GeometricStaticSolver::bytes() const {
  const Petsc& p = *petsc_;
  const auto sparse = [](const RowSparse& a) {
    return static_cast<std::size_t>(a.nonZeros()) * 12 + static_cast<std::size_t>(a.rows()) * 4;
  };
  return sparse(p.level.matrix) + sparse(p.level.interpolation) +
         static_cast<std::size_t>(p.level.nodes.size()) * 8 +
         static_cast<std::size_t>(p.diagonal.size() + p.in.size() + p.out.size() + last_.size()) *
             8;
}

void GeometricStaticSolver::make_levels() {
  Petsc& p = *petsc_;
  const auto n = static_cast<PetscInt>(op_.dofs());
  p.in.resize(n);
  p.out.resize(n);
  petsc_check(MatCreateShell(PETSC_COMM_SELF, n, n, n, n, &p, &p.fine), "MatCreateShell");
  petsc_check(
      MatShellSetOperation(p.fine, MATOP_MULT, reinterpret_cast<void (*)(void)>(&Petsc::multiply)),
      "MatShellSetOperation");
  petsc_check(MatShellSetOperation(p.fine, MATOP_GET_DIAGONAL,
                                   reinterpret_cast<void (*)(void)>(&Petsc::get_diagonal)),
              "MatShellSetOperation");
  petsc_check(MatSetBlockSize(p.fine, 3), "MatSetBlockSize");
  petsc_check(MatSetOption(p.fine, MAT_SPD, PETSC_TRUE), "MatSetOption");
  // The coarse matrix and the interpolation share the level's arrays (no copy).
  RowSparse& a = p.level.matrix;
  const auto m = static_cast<PetscInt>(a.rows());
  petsc_check(MatCreateSeqAIJWithArrays(PETSC_COMM_SELF, m, m, a.outerIndexPtr(), a.innerIndexPtr(),
                                        a.valuePtr(), &p.coarse),
              "MatCreateSeqAIJWithArrays");
  petsc_check(MatSetBlockSize(p.coarse, 3), "MatSetBlockSize");  // nodes, for GAMG's aggregates
  petsc_check(MatSetOption(p.coarse, MAT_SPD, PETSC_TRUE), "MatSetOption");
  RowSparse& t = p.level.interpolation;
  petsc_check(MatCreateSeqAIJWithArrays(PETSC_COMM_SELF, static_cast<PetscInt>(t.rows()),
                                        static_cast<PetscInt>(t.cols()), t.outerIndexPtr(),
                                        t.innerIndexPtr(), t.valuePtr(), &p.node_interpolation),
              "MatCreateSeqAIJWithArrays");
  petsc_check(MatCreateMAIJ(p.node_interpolation, 3, &p.interpolation), "MatCreateMAIJ");
  // The coarse solve's near-null space: the rigid-body modes of the coarse nodes.
  Vec coordinates = nullptr;
  MatNullSpace modes = nullptr;
  petsc_check(VecCreateSeqWithArray(PETSC_COMM_SELF, 3, static_cast<PetscInt>(p.level.nodes.size()),
                                    p.level.nodes.data(), &coordinates),
              "VecCreateSeqWithArray");
  petsc_check(MatNullSpaceCreateRigidBody(coordinates, &modes), "MatNullSpaceCreateRigidBody");
  petsc_check(MatSetNearNullSpace(p.coarse, modes), "MatSetNearNullSpace");
  MatNullSpaceDestroy(&modes);  // (the matrix holds it)
  VecDestroy(&coordinates);
  petsc_check(VecCreateSeqWithArray(PETSC_COMM_SELF, 3, n, nullptr, &p.x), "VecCreateSeqWithArray");
  petsc_check(VecCreateSeqWithArray(PETSC_COMM_SELF, 3, n, nullptr, &p.b), "VecCreateSeqWithArray");
}

void GeometricStaticSolver::build_solver() {
  Petsc& p = *petsc_;
  p.ksp = static_cg(PETSC_COMM_SELF, p.fine, p.fine, kTolerance);
  set_two_level_multigrid(p.ksp, p.fine, p.coarse, p.interpolation);
  petsc_check(KSPSetFromOptions(p.ksp), "KSPSetFromOptions");
  set_stop_test(p.ksp, op_, p.stop);
  {
    const ScopedPetscOption clear(kClearProducts, "true");  // (GAMG's on the coarse level)
    petsc_check(KSPSetUp(p.ksp), "KSPSetUp (the geometric multigrid's levels)");
  }
  levels_ = two_level_multigrid_levels(p.ksp);
}

Eigen::VectorXd GeometricStaticSolver::solve(const Eigen::VectorXd& f) {
  Petsc& p = *petsc_;
  return solve_static(p.ksp, p.x, p.b, p.stop, f, last_, iterations_,
                      "CG with the geometric multigrid");
}

}  // namespace rumble::fem
