#include "distributed/rank_petsc.hpp"

#include <algorithm>
#include <sstream>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "distributed/rank_agreement.hpp"
#include "statics/petsc_session.hpp"

namespace rumble::fem {

static_assert(std::is_same_v<PetscInt, int>, "PETSc's indices are ints (Debian's 32-bit PETSc)");
static_assert(std::is_same_v<PetscScalar, double>, "a real, double PETSc");

namespace {

// Each rank's part's blocks (K's rows of its nodes, row-major per node as CsrMatrix keeps them)
// times c.stiffness and, at its owned nodes, c.mass M and the boundary's blocks of c: into m by
// block rows and columns, added.
void add_blocks(Mat m, const SoilOperator& op, const std::vector<PetscInt>& row,
                const std::vector<int>& owner, int rank, const Combination& c) {
  const CsrMatrix& K = op.stiffness();
  std::vector<PetscInt> columns;
  std::vector<double> scaled;  // (a node's block row times c.stiffness, where it is not 1)
  for (std::int32_t i = 0; i < static_cast<std::int32_t>(row.size()); ++i) {
    const std::int64_t degree = K.degree(i);
    columns.resize(static_cast<std::size_t>(degree));
    for (std::int64_t p = 0; p < degree; ++p) columns[p] = row[K.neighbours(i)[p]];
    // (node i's three rows hold 3 x degree values each: one block row, row-oriented)
    const double* values = K.value().data() + K.row_start()[3 * i];
    if (c.stiffness != 1.0) {
      scaled.assign(values, values + 9 * degree);
      for (double& v : scaled) v *= c.stiffness;
      values = scaled.data();
    }
    petsc_check(MatSetValuesBlocked(m, 1, &row[i], static_cast<PetscInt>(degree), columns.data(),
                                    values, ADD_VALUES),
                "MatSetValuesBlocked");
  }
  // (each copy of a node holds its whole mass and block: added by its owner alone)
  for (const BoundaryNode& node : op.boundary()) {
    if (owner[node.node] != rank) continue;
    double block[9];
    boundary_block(node, c, block);
    petsc_check(MatSetValuesBlocked(m, 1, &row[node.node], 1, &row[node.node], block, ADD_VALUES),
                "MatSetValuesBlocked");
  }
  if (c.mass != 0.0)
    for (std::int32_t i = 0; i < static_cast<std::int32_t>(row.size()); ++i) {
      if (owner[i] != rank) continue;
      const double m_i = c.mass * op.mass()[i];
      const double block[9] = {m_i, 0.0, 0.0, 0.0, m_i, 0.0, 0.0, 0.0, m_i};
      petsc_check(MatSetValuesBlocked(m, 1, &row[i], 1, &row[i], block, ADD_VALUES),
                  "MatSetValuesBlocked");
    }
  petsc_check(MatAssemblyBegin(m, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
  petsc_check(MatAssemblyEnd(m, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
}

// Preallocates m's owned block rows (nodes) from this rank's part: each owned node's blocks in
// the owned columns and in the others, as its row of K holds them; a shared node's row also
// gathers the pieces of the ranks holding a ghost copy, whose columns this rank does not hold:
// their blocks (each ghost copy's degree, summed to the owner) are added to both counts, an upper
// bound on the shared nodes only (a few % of a rank's). MATPREALLOCATOR, which this replaces,
// took a second pass over every block into a hash set (65 MB more on rank 0 at 1.0e6 DOFs).
void preallocate(Mat m, const CsrMatrix& K, const MeshPartition& part, const RankRows& rows,
                 int rank) {
  const auto count = static_cast<PetscInt>(rows.owned.size());
  std::vector<double> others(static_cast<std::size_t>(part.shared), 0.0);
  for (std::int32_t i = 0; i < part.shared; ++i)
    if (!part.owns(i, rank)) others[i] = static_cast<double>(K.degree(i));
  part.halo->sum_to_roots(others.data(), others.data(), 1);  // (a ghost adds to its owner)
  std::vector<PetscInt> diagonal(rows.owned.size(), 0), off(rows.owned.size(), 0);
  for (std::size_t k = 0; k < rows.owned.size(); ++k) {
    const std::int32_t i = rows.owned[k];
    for (std::int64_t q = 0; q < K.degree(i); ++q) {
      const PetscInt column = rows.row[K.neighbours(i)[q]];
      ++(column >= rows.first && column < rows.first + count ? diagonal[k] : off[k]);
    }
    if (i >= part.shared) continue;
    const auto extra = static_cast<PetscInt>(others[i]);
    diagonal[k] = std::min(diagonal[k] + extra, count);
    off[k] = std::min(off[k] + extra, rows.total - count);
  }
  petsc_check(MatXAIJSetPreallocation(m, 3, diagonal.data(), off.data(), nullptr, nullptr),
              "MatXAIJSetPreallocation");
}

}  // namespace

void RankSolve::clear() {
  KSPDestroy(&ksp);
  VecDestroy(&x);
  VecDestroy(&b);
  MatDestroy(&a);
}

RankRows number_rows(const MeshPartition& part, MPI_Comm comm) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  RankRows rows;
  for (std::int32_t i = 0; i < part.nodes(); ++i)
    if (part.owns(i, rank)) rows.owned.push_back(i);
  const auto count = static_cast<PetscInt>(rows.owned.size());
  MPI_Exscan(&count, &rows.first, 1, MPIU_INT, MPI_SUM, comm);
  if (rank == 0) rows.first = 0;  // (MPI_Exscan leaves rank 0's undefined)
  MPI_Allreduce(&count, &rows.total, 1, MPIU_INT, MPI_SUM, comm);
  rows.row.assign(static_cast<std::size_t>(part.nodes()), -1);
  for (std::size_t k = 0; k < rows.owned.size(); ++k)
    rows.row[rows.owned[k]] = rows.first + static_cast<PetscInt>(k);
  part.halo->to_leaves(rows.row.data(), rows.row.data(), 1);
  return rows;
}

Mat assemble_part_matrix(const MeshPartition& part, const SoilOperator& op, const RankRows& rows,
                         MPI_Comm comm) {
  return assemble_part_combination(part, op, rows, {.stiffness = 1.0, .springs = true}, comm);
}

Mat assemble_part_combination(const MeshPartition& part, const SoilOperator& op,
                              const RankRows& rows, const Combination& combination, MPI_Comm comm) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  const auto count = static_cast<PetscInt>(rows.owned.size());
  Mat m = nullptr;
  petsc_check(MatCreate(comm, &m), "MatCreate");
  petsc_check(MatSetType(m, MATAIJ), "MatSetType");
  petsc_check(MatSetSizes(m, 3 * count, 3 * count, PETSC_DETERMINE, PETSC_DETERMINE),
              "MatSetSizes");
  petsc_check(MatSetBlockSize(m, 3), "MatSetBlockSize");
  preallocate(m, op.stiffness(), part, rows, rank);
  add_blocks(m, op, rows.row, part.owner, rank, combination);
  std::vector<PetscInt> fixed;  // the owned fixed nodes' DOFs: identity rows and columns
  for (const std::int32_t i : rows.owned)
    if (op.fixed()[i])
      for (int c = 0; c < 3; ++c) fixed.push_back(3 * rows.row[i] + c);
  petsc_check(MatZeroRowsColumns(m, static_cast<PetscInt>(fixed.size()), fixed.data(), 1.0, nullptr,
                                 nullptr),
              "MatZeroRowsColumns");
  petsc_check(MatSetOption(m, MAT_SPD, PETSC_TRUE), "MatSetOption");
  return m;
}

void set_rigid_body_modes(Mat m, const MeshPartition& part, const RankRows& rows, MPI_Comm comm) {
  std::vector<double> coordinates;  // (statics/petsc_static_solver.cpp's modes, owned nodes)
  for (const std::int32_t i : rows.owned)
    for (int c = 0; c < 3; ++c) coordinates.push_back(part.mesh.nodes(c, i));
  Vec at = nullptr;
  MatNullSpace modes = nullptr;
  petsc_check(VecCreateMPIWithArray(comm, 3, static_cast<PetscInt>(coordinates.size()),
                                    PETSC_DETERMINE, coordinates.data(), &at),
              "VecCreateMPIWithArray");
  petsc_check(MatNullSpaceCreateRigidBody(at, &modes), "MatNullSpaceCreateRigidBody");
  petsc_check(MatSetNearNullSpace(m, modes), "MatSetNearNullSpace");
  MatNullSpaceDestroy(&modes);  // (the matrix holds it)
  VecDestroy(&at);
}

SetUpOptions::SetUpOptions() {
  char via[32] = "";
  PetscBool set = PETSC_FALSE;
  petsc_check(PetscOptionsGetString(nullptr, nullptr, "-matptap_via", via, sizeof via, &set),
              "PetscOptionsGetString");
  rap_ = set && std::string(via) == "rap";
  if (rap_) petsc_check(PetscOptionsClearValue(nullptr, "-matptap_via"), "PetscOptionsClearValue");
}

SetUpOptions::~SetUpOptions() {  // (errors ignored: a destructor)
  if (rap_) PetscOptionsSetValue(nullptr, "-matptap_via", "rap");
}

Eigen::VectorXd solve_on_ranks(KSP ksp, Vec x, Vec b, PetscStopTest& stop,
                               const MeshPartition& part, const RankRows& rows,
                               const std::vector<char>& fixed, const Eigen::VectorXd& f,
                               int& iterations, const char* method) {
  PetscScalar* load = nullptr;
  petsc_check(VecGetArray(b, &load), "VecGetArray");
  for (std::size_t k = 0; k < rows.owned.size(); ++k)
    for (int c = 0; c < 3; ++c)
      load[3 * k + c] = fixed[rows.owned[k]] ? 0.0 : f[3 * rows.owned[k] + c];
  petsc_check(VecRestoreArray(b, &load), "VecRestoreArray");
  PetscReal largest = 0.0;  // (over the ranks: every rank takes the same branch)
  petsc_check(VecNorm(b, NORM_INFINITY, &largest), "VecNorm");
  iterations = 0;
  if (largest == 0.0) {  // no load on a free DOF: at rest
    petsc_check(VecSet(x, 0.0), "VecSet");
  } else {
    const PetscErrorCode code = KSPSolve(ksp, b, x);
    // (every rank left CG at the same iteration, or at its end: the ranks agree why, a rank's
    // failed product or rank 0's stop, before a failure of PETSc's own is thrown)
    const MPI_Comm comm = PetscObjectComm(reinterpret_cast<PetscObject>(ksp));
    agree(comm, std::exchange(stop.failed, nullptr),
          std::exchange(stop.stopped, nullptr) != nullptr);
    petsc_check(code, "KSPSolve");
    PetscInt its = 0;
    KSPConvergedReason reason = KSP_CONVERGED_ITERATING;
    KSPGetIterationNumber(ksp, &its);
    KSPGetConvergedReason(ksp, &reason);
    iterations = static_cast<int>(its);
    if (reason < 0) {  // (the same on every rank: rank 0 says it, every rank throws)
      PetscReal residual = 0.0;
      KSPGetResidualNorm(ksp, &residual);
      std::ostringstream m;
      m << "fem: " << method << " did not converge after " << iterations
        << " iterations (PETSc's reason " << static_cast<int>(reason) << ", residual " << residual
        << " N): check the soil's parameters";
      on_root(comm, [&m] { throw std::runtime_error(m.str()); });
    }
  }
  Eigen::VectorXd u = Eigen::VectorXd::Zero(3 * static_cast<Eigen::Index>(part.nodes()));
  const PetscScalar* solution = nullptr;
  petsc_check(VecGetArrayRead(x, &solution), "VecGetArrayRead");
  for (std::size_t k = 0; k < rows.owned.size(); ++k)
    for (int c = 0; c < 3; ++c) u[3 * rows.owned[k] + c] = solution[3 * k + c];
  petsc_check(VecRestoreArrayRead(x, &solution), "VecRestoreArrayRead");
  part.halo->to_leaves(u.data(), u.data(), 3);  // (the ghosts take their owners' values)
  return u;
}

}  // namespace rumble::fem
