#include "distributed/distributed_statics.hpp"

#include <petscksp.h>

#include <algorithm>
#include <chrono>
#include <sstream>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "statics/petsc_cg.hpp"
#include "statics/petsc_session.hpp"

namespace rumble::fem {

static_assert(std::is_same_v<PetscInt, int>, "PETSc's indices are ints (Debian's 32-bit PETSc)");
static_assert(std::is_same_v<PetscScalar, double>, "a real, double PETSc");

struct DistributedStatics::Petsc {
  ~Petsc() {  // (errors ignored: a destructor)
    KSPDestroy(&ksp);
    VecDestroy(&x);
    VecDestroy(&b);
    MatDestroy(&a);
  }
  std::shared_ptr<PetscSession> session = PetscSession::get();
  MPI_Comm comm = MPI_COMM_NULL;
  std::vector<std::int32_t> owned;  // the local nodes this rank owns, in local order
  std::vector<char> fixed;          // per owned node: fixed (a zero load)
  std::vector<PetscInt> row;        // per local node: its block row (node) in the matrix
  Mat a = nullptr;
  Vec x = nullptr, b = nullptr;  // x: the last solution (CG's start)
  KSP ksp = nullptr;
};

namespace {

// Each rank's part's blocks (K's rows of its nodes, row-major per node as CsrMatrix keeps them)
// and, at its owned boundary nodes, S: into m by block rows and columns, added.
void add_blocks(Mat m, const SoilOperator& op, const std::vector<PetscInt>& row,
                const std::vector<int>& owner, int rank) {
  const CsrMatrix& K = op.stiffness();
  std::vector<PetscInt> columns;
  for (std::int32_t i = 0; i < static_cast<std::int32_t>(row.size()); ++i) {
    const std::int64_t degree = K.degree(i);
    columns.resize(static_cast<std::size_t>(degree));
    for (std::int64_t p = 0; p < degree; ++p) columns[p] = row[K.neighbours(i)[p]];
    // (node i's three rows hold 3 x degree values each: one block row, row-oriented)
    petsc_check(MatSetValuesBlocked(m, 1, &row[i], static_cast<PetscInt>(degree), columns.data(),
                                    K.value().data() + K.row_start()[3 * i], ADD_VALUES),
                "MatSetValuesBlocked");
  }
  for (const BoundaryNode& node : op.boundary()) {
    if (owner[node.node] != rank) continue;  // (each copy holds the whole block: added once)
    double spring[9];
    for (int c = 0; c < 3; ++c)
      for (int d = 0; d < 3; ++d) spring[3 * c + d] = node.spring(c, d);
    petsc_check(MatSetValuesBlocked(m, 1, &row[node.node], 1, &row[node.node], spring, ADD_VALUES),
                "MatSetValuesBlocked");
  }
  petsc_check(MatAssemblyBegin(m, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
  petsc_check(MatAssemblyEnd(m, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
}

// PETSc's process-wide options for the span of GAMG's set-up on the ranks (MatPtAP and
// MatMatMult read them without a prefix), each unless PETSC_OPTIONS gave it, restored after:
// - "-matptap_via": the session's "rap" (one process's fastest, statics/petsc_session.cpp) is no
//   algorithm of the ranks' matrices (MPIAIJ's: scalable, nonscalable, allatonce, ...): their
//   default, scalable, for GAMG's Galerkin products (a "rap" in PETSC_OPTIONS is taken as the
//   session's);
// - "-mat_product_clear": each product's intermediates (A P's local rows, P's rows from the
//   other ranks, ...) freed once it is formed. PETSc keeps them to form the product again from a
//   changed matrix, which the statics never do: at 1.0e6 DOFs on 2 ranks a rank's peak fell from
//   2.25 to 1.94 GB, and what it holds through the solves from 2.25 to 1.39 GB, with the same
//   hierarchy and iterations (docs/fem-soil.md §8).
class SetUpOptions {
 public:
  SetUpOptions() {
    char via[32] = "";
    PetscBool set = PETSC_FALSE;
    petsc_check(PetscOptionsGetString(nullptr, nullptr, "-matptap_via", via, sizeof via, &set),
                "PetscOptionsGetString");
    rap_ = set && std::string(via) == "rap";
    if (rap_)
      petsc_check(PetscOptionsClearValue(nullptr, "-matptap_via"), "PetscOptionsClearValue");
    petsc_check(PetscOptionsHasName(nullptr, nullptr, "-mat_product_clear", &set),
                "PetscOptionsHasName");
    clear_ = !set;
    if (clear_)
      petsc_check(PetscOptionsSetValue(nullptr, "-mat_product_clear", "true"),
                  "PetscOptionsSetValue");
  }
  ~SetUpOptions() {  // (errors ignored: a destructor)
    if (rap_) PetscOptionsSetValue(nullptr, "-matptap_via", "rap");
    if (clear_) PetscOptionsClearValue(nullptr, "-mat_product_clear");
  }
  SetUpOptions(const SetUpOptions&) = delete;
  SetUpOptions& operator=(const SetUpOptions&) = delete;

 private:
  bool rap_ = false, clear_ = false;
};

// Preallocates m's owned block rows (nodes) from this rank's part: each owned node's blocks in
// the owned columns and in the others, as its row of K holds them; a shared node's row also
// gathers the pieces of the ranks holding a ghost copy, whose columns this rank does not hold:
// their blocks (each ghost copy's degree, summed to the owner) are added to both counts, an upper
// bound on the shared nodes only (a few % of a rank's). MATPREALLOCATOR, which this replaces,
// took a second pass over every block into a hash set (65 MB more on rank 0 at 1.0e6 DOFs).
void preallocate(Mat m, const CsrMatrix& K, const MeshPartition& part,
                 const std::vector<std::int32_t>& owned, const std::vector<PetscInt>& row,
                 MPI_Comm comm) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  const auto count = static_cast<PetscInt>(owned.size());
  PetscInt total = 0;
  MPI_Allreduce(&count, &total, 1, MPIU_INT, MPI_SUM, comm);
  const PetscInt first = owned.empty() ? 0 : row[owned.front()];
  std::vector<double> others(static_cast<std::size_t>(part.shared), 0.0);
  for (std::int32_t i = 0; i < part.shared; ++i)
    if (!part.owns(i, rank)) others[i] = static_cast<double>(K.degree(i));
  part.halo->sum_to_roots(others.data(), others.data(), 1);  // (a ghost adds to its owner)
  std::vector<PetscInt> diagonal(owned.size(), 0), off(owned.size(), 0);
  for (std::size_t k = 0; k < owned.size(); ++k) {
    const std::int32_t i = owned[k];
    for (std::int64_t q = 0; q < K.degree(i); ++q) {
      const PetscInt column = row[K.neighbours(i)[q]];
      ++(column >= first && column < first + count ? diagonal[k] : off[k]);
    }
    if (i >= part.shared) continue;
    const auto extra = static_cast<PetscInt>(others[i]);
    diagonal[k] = std::min(diagonal[k] + extra, count);
    off[k] = std::min(off[k] + extra, total - count);
  }
  petsc_check(MatXAIJSetPreallocation(m, 3, diagonal.data(), off.data(), nullptr, nullptr),
              "MatXAIJSetPreallocation");
}

// An empty matrix of the owned nodes' rows (3 per node, blocks of 3) of `type`.
Mat owned_rows(MPI_Comm comm, PetscInt nodes, MatType type) {
  Mat m = nullptr;
  petsc_check(MatCreate(comm, &m), "MatCreate");
  petsc_check(MatSetType(m, type), "MatSetType");
  petsc_check(MatSetSizes(m, 3 * nodes, 3 * nodes, PETSC_DETERMINE, PETSC_DETERMINE),
              "MatSetSizes");
  petsc_check(MatSetBlockSize(m, 3), "MatSetBlockSize");
  return m;
}

}  // namespace

DistributedStatics::DistributedStatics(const MeshPartition& part, const SoilOperator& op,
                                       MPI_Comm comm)
    : part_(part), petsc_(std::make_unique<Petsc>()) {
  const auto start = std::chrono::steady_clock::now();
  Petsc& p = *petsc_;
  p.comm = comm;
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  for (std::int32_t i = 0; i < part.nodes(); ++i)
    if (part.owns(i, rank)) p.owned.push_back(i);
  // The matrix's nodes: each rank's owned ones in turn, in local order; a ghost takes its
  // owner's number through the halo.
  PetscInt count = static_cast<PetscInt>(p.owned.size()), offset = 0;
  MPI_Exscan(&count, &offset, 1, MPIU_INT, MPI_SUM, comm);
  if (rank == 0) offset = 0;  // (MPI_Exscan leaves rank 0's undefined)
  p.row.assign(static_cast<std::size_t>(part.nodes()), -1);
  for (std::size_t k = 0; k < p.owned.size(); ++k)
    p.row[p.owned[k]] = offset + static_cast<PetscInt>(k);
  part.halo->to_leaves(p.row.data(), p.row.data(), 1);
  assemble(op);
  build_solver();
  setup_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

DistributedStatics::~DistributedStatics() = default;

void DistributedStatics::assemble(const SoilOperator& op) {
  Petsc& p = *petsc_;
  int rank = 0;
  MPI_Comm_rank(p.comm, &rank);
  const auto count = static_cast<PetscInt>(p.owned.size());
  p.a = owned_rows(p.comm, count, MATAIJ);
  preallocate(p.a, op.stiffness(), part_, p.owned, p.row, p.comm);
  add_blocks(p.a, op, p.row, part_.owner, rank);
  std::vector<PetscInt> fixed;  // the owned fixed nodes' DOFs: identity rows and columns
  for (const std::int32_t i : p.owned) {
    p.fixed.push_back(op.fixed()[i]);
    if (op.fixed()[i])
      for (int c = 0; c < 3; ++c) fixed.push_back(3 * p.row[i] + c);
  }
  petsc_check(MatZeroRowsColumns(p.a, static_cast<PetscInt>(fixed.size()), fixed.data(), 1.0,
                                 nullptr, nullptr),
              "MatZeroRowsColumns");
  petsc_check(MatSetOption(p.a, MAT_SPD, PETSC_TRUE), "MatSetOption");
  petsc_check(MatCreateVecs(p.a, &p.x, &p.b), "MatCreateVecs");
  petsc_check(VecSet(p.x, 0.0), "VecSet");
}

void DistributedStatics::build_solver() {
  Petsc& p = *petsc_;
  // The rigid-body modes from the owned nodes' coordinates (statics/petsc_static_solver.cpp).
  std::vector<double> coordinates;
  for (const std::int32_t i : p.owned)
    for (int c = 0; c < 3; ++c) coordinates.push_back(part_.mesh.nodes(c, i));
  Vec at = nullptr;
  MatNullSpace modes = nullptr;
  petsc_check(VecCreateMPIWithArray(p.comm, 3, static_cast<PetscInt>(coordinates.size()),
                                    PETSC_DETERMINE, coordinates.data(), &at),
              "VecCreateMPIWithArray");
  petsc_check(MatNullSpaceCreateRigidBody(at, &modes), "MatNullSpaceCreateRigidBody");
  petsc_check(MatSetNearNullSpace(p.a, modes), "MatSetNearNullSpace");
  MatNullSpaceDestroy(&modes);  // (the matrix holds it)
  VecDestroy(&at);
  PC pc = nullptr;
  p.ksp = static_cg(p.comm, p.a, p.a, kTolerance);
  petsc_check(KSPGetPC(p.ksp, &pc), "KSPGetPC");
  petsc_check(PCSetType(pc, PCGAMG), "PCSetType");
  petsc_check(KSPSetFromOptions(p.ksp), "KSPSetFromOptions");
  PetscErrorCode code = 0;
  {
    const SetUpOptions options;
    code = KSPSetUp(p.ksp);
  }
  petsc_check(code, "KSPSetUp (GAMG's hierarchy)");
  PetscInt levels = 0;
  petsc_check(PCMGGetLevels(pc, &levels), "PCMGGetLevels");
  levels_ = static_cast<int>(levels);
}

Eigen::VectorXd DistributedStatics::solve(const Eigen::VectorXd& f) {
  Petsc& p = *petsc_;
  PetscScalar* load = nullptr;
  petsc_check(VecGetArray(p.b, &load), "VecGetArray");
  for (std::size_t k = 0; k < p.owned.size(); ++k)
    for (int c = 0; c < 3; ++c) load[3 * k + c] = p.fixed[k] ? 0.0 : f[3 * p.owned[k] + c];
  petsc_check(VecRestoreArray(p.b, &load), "VecRestoreArray");
  PetscReal largest = 0.0;
  petsc_check(VecNorm(p.b, NORM_INFINITY, &largest), "VecNorm");
  iterations_ = 0;
  if (largest == 0.0) {  // no load on a free DOF: at rest
    petsc_check(VecSet(p.x, 0.0), "VecSet");
  } else {
    petsc_check(KSPSolve(p.ksp, p.b, p.x), "KSPSolve");
    PetscInt iterations = 0;
    KSPConvergedReason reason = KSP_CONVERGED_ITERATING;
    KSPGetIterationNumber(p.ksp, &iterations);
    KSPGetConvergedReason(p.ksp, &reason);
    iterations_ = static_cast<int>(iterations);
    if (reason < 0) {  // (the same on every rank: each throws)
      PetscReal residual = 0.0;
      KSPGetResidualNorm(p.ksp, &residual);
      std::ostringstream m;
      m << "fem: the static solve on the ranks (PETSc's CG with GAMG) did not converge after "
        << iterations << " iterations (PETSc's reason " << static_cast<int>(reason) << ", residual "
        << residual
        << " N): check the soil's parameters; statics.solver \"multigrid\" solves on rank 0";
      throw std::runtime_error(m.str());
    }
  }
  Eigen::VectorXd u = Eigen::VectorXd::Zero(3 * static_cast<Eigen::Index>(part_.nodes()));
  const PetscScalar* solution = nullptr;
  petsc_check(VecGetArrayRead(p.x, &solution), "VecGetArrayRead");
  for (std::size_t k = 0; k < p.owned.size(); ++k)
    for (int c = 0; c < 3; ++c) u[3 * p.owned[k] + c] = solution[3 * k + c];
  petsc_check(VecRestoreArrayRead(p.x, &solution), "VecRestoreArrayRead");
  part_.halo->to_leaves(u.data(), u.data(), 3);  // (the ghosts take their owners' values)
  return u;
}

}  // namespace rumble::fem
