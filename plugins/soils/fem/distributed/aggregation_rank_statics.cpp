#include "distributed/aggregation_rank_statics.hpp"

#include <petscksp.h>

#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <utility>
#include <vector>

#include "distributed/rank_fine_level.hpp"
#include "distributed/rank_petsc.hpp"
#include "operator/effective_matrix.hpp"
#include "statics/node_aggregates.hpp"
#include "statics/petsc_cg.hpp"
#include "statics/petsc_session.hpp"

namespace rumble::fem {

struct AggregationRankStatics::Petsc {
  Petsc(const MeshPartition& part, const SoilOperator& op, MPI_Comm comm) : level(part, op, comm) {}
  ~Petsc() {  // (errors ignored: a destructor)
    KSPDestroy(&ksp);
    MatDestroy(&interpolation);
    MatDestroy(&coarse);
  }
  RankFineLevel level;
  Mat coarse = nullptr;         // A_c = P^T (K + S) P, block size 6
  Mat interpolation = nullptr;  // P: owned fine DOFs x this rank's coarse DOFs
  KSP ksp = nullptr;
};

namespace {

/// The aggregates and P on this rank's part (local numbers), until the coarse matrix is made.
struct FirstLevel {
  const MeshPartition* part = nullptr;
  const RankFineLevel* fine = nullptr;
  int rank = 0;
  NodeGraph graph;
  NodeAggregates aggregates;   // on this rank's owned free nodes
  PetscInt first = 0;          // this rank's first aggregate over the ranks
  PetscInt total = 0;          // the aggregates over the ranks
  std::vector<PetscInt> base;  // per local node: its aggregate's first coarse DOF, -1: none
  RigidProlongator p;          // its blocks on every local node (a ghost's from its owner)
};

constexpr int kCarried = 1 + 3 * kModes;  // a shared node's base and block, to its ghosts

// The distinct coarse blocks (aggregates over the ranks) of node i and its neighbours.
int distinct_blocks(const NodeGraph& g, const std::vector<PetscInt>& base, std::int32_t i,
                    std::vector<PetscInt>& scratch) {
  scratch.clear();
  if (base[i] >= 0) scratch.push_back(base[i] / kModes);
  for (std::int32_t k = 0; k < g.degree(i); ++k)
    if (base[g.of(i)[k]] >= 0) scratch.push_back(base[g.of(i)[k]] / kModes);
  std::sort(scratch.begin(), scratch.end());
  return static_cast<int>(std::unique(scratch.begin(), scratch.end()) - scratch.begin());
}

/// The aggregates of this rank's owned free nodes, their blocks of P, a ghost's from its owner.
FirstLevel first_level(const MeshPartition& part, const RankFineLevel& f) {
  int rank = 0;
  MPI_Comm_rank(f.comm, &rank);
  const std::int32_t n = part.nodes();
  std::vector<char> candidate(static_cast<std::size_t>(n), 0);  // owned and free
  for (std::int32_t i = 0; i < n; ++i) candidate[i] = part.owns(i, rank) && !f.fixed[i];
  FirstLevel c;
  c.part = &part;
  c.fine = &f;
  c.rank = rank;
  c.graph = node_graph(part.mesh);
  c.aggregates = aggregate_nodes(c.graph, candidate);
  c.p = rigid_prolongator(part.mesh.nodes, c.aggregates);
  const PetscInt count = c.aggregates.count;
  MPI_Exscan(&count, &c.first, 1, MPIU_INT, MPI_SUM, f.comm);
  if (rank == 0) c.first = 0;  // (MPI_Exscan leaves rank 0's undefined)
  MPI_Allreduce(&count, &c.total, 1, MPIU_INT, MPI_SUM, f.comm);
  c.base.assign(static_cast<std::size_t>(n), -1);
  for (std::int32_t i = 0; i < n; ++i)
    if (c.aggregates.of[i] >= 0) c.base[i] = kModes * (c.first + c.aggregates.of[i]);
  // a ghost's aggregate and block are its owner's
  std::vector<double> carried(kCarried * static_cast<std::size_t>(part.shared), 0.0);
  for (std::int32_t i = 0; i < part.shared; ++i) {
    carried[kCarried * i] = static_cast<double>(c.base[i]);  // (exact: below 2^53)
    std::copy_n(c.p.blocks.data() + 3 * kModes * i, 3 * kModes, carried.data() + kCarried * i + 1);
  }
  part.halo->to_leaves(carried.data(), carried.data(), kCarried);
  for (std::int32_t i = 0; i < part.shared; ++i) {
    if (part.owns(i, rank)) continue;
    c.base[i] = static_cast<PetscInt>(carried[kCarried * i]);
    std::copy_n(carried.data() + kCarried * i + 1, 3 * kModes, c.p.blocks.data() + 3 * kModes * i);
  }
  return c;
}

/// P: each owned free node's 3 rows, its aggregate's columns (all on this rank).
Mat prolongator(const FirstLevel& c) {
  const RankFineLevel& f = *c.fine;
  const PetscInt count = c.aggregates.count;
  const auto owned = static_cast<PetscInt>(f.rows.owned.size());
  std::vector<PetscInt> per_row(3 * f.rows.owned.size(), kModes), none(per_row.size(), 0);
  Mat P = nullptr;
  petsc_check(MatCreate(f.comm, &P), "MatCreate");
  petsc_check(MatSetType(P, MATAIJ), "MatSetType");
  petsc_check(MatSetSizes(P, 3 * owned, kModes * count, PETSC_DETERMINE, PETSC_DETERMINE),
              "MatSetSizes");
  petsc_check(MatXAIJSetPreallocation(P, 1, per_row.data(), none.data(), nullptr, nullptr),
              "MatXAIJSetPreallocation");
  PetscInt columns[kModes];
  double values[kModes];
  for (const std::int32_t i : f.rows.owned) {
    if (c.base[i] < 0) continue;  // (a held node takes no correction)
    for (int r = 0; r < 3; ++r) {
      int used = 0;
      for (int k = 0; k < kModes; ++k) {
        if (c.p.dropped[c.base[i] - kModes * c.first + k]) continue;
        columns[used] = c.base[i] + k;
        values[used++] = c.p.blocks[3 * kModes * static_cast<std::size_t>(i) + kModes * r + k];
      }
      const PetscInt row = 3 * f.rows.row[i] + r;
      petsc_check(MatSetValues(P, 1, &row, used, columns, values, INSERT_VALUES), "MatSetValues");
    }
  }
  petsc_check(MatAssemblyBegin(P, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
  petsc_check(MatAssemblyEnd(P, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
  return P;
}

/// A_c's MPIAIJ, its 6 x 6 blocks preallocated.
Mat preallocated_coarse(const FirstLevel& c) {
  const RankFineLevel& f = *c.fine;
  const MeshPartition& part = *c.part;
  const int rank = c.rank;
  const PetscInt count = c.aggregates.count;
  // Preallocation in 6 x 6 blocks: an aggregate's row holds the aggregates of its nodes and
  // their neighbours here, and what other ranks' tetrahedra add at its shared nodes (each ghost
  // copy's distinct neighbouring aggregates, summed to the owner: an upper bound, added to both
  // counts, as the ranks' K is preallocated, rank_petsc.cpp).
  std::vector<std::vector<PetscInt>> blocks(static_cast<std::size_t>(count));
  std::vector<PetscInt> scratch;
  for (std::int32_t i = 0; i < part.nodes(); ++i) {
    const std::int32_t a = c.aggregates.of[i];
    if (a < 0) continue;
    const int distinct = distinct_blocks(c.graph, c.base, i, scratch);
    blocks[a].insert(blocks[a].end(), scratch.begin(), scratch.begin() + distinct);
  }
  std::vector<double> others(static_cast<std::size_t>(part.shared), 0.0);
  for (std::int32_t i = 0; i < part.shared; ++i)
    if (!part.owns(i, rank) && c.base[i] >= 0)
      others[i] = distinct_blocks(c.graph, c.base, i, scratch);
  part.halo->sum_to_roots(others.data(), others.data(), 1);
  std::vector<PetscInt> diagonal(blocks.size(), 0), off(blocks.size(), 0);
  for (std::size_t a = 0; a < blocks.size(); ++a) {
    std::sort(blocks[a].begin(), blocks[a].end());
    const auto end = std::unique(blocks[a].begin(), blocks[a].end());
    for (auto b = blocks[a].begin(); b != end; ++b)
      ++(*b >= c.first && *b < c.first + count ? diagonal[a] : off[a]);
    std::vector<PetscInt>().swap(blocks[a]);
  }
  for (std::int32_t i = 0; i < part.shared; ++i)
    if (c.aggregates.of[i] >= 0) {
      const auto extra = static_cast<PetscInt>(others[i]);
      diagonal[c.aggregates.of[i]] += extra;
      off[c.aggregates.of[i]] += extra;
    }
  for (std::size_t a = 0; a < blocks.size(); ++a) {
    diagonal[a] = std::min(diagonal[a], count);
    off[a] = std::min(off[a], c.total - count);
  }
  Mat A = nullptr;
  petsc_check(MatCreate(f.comm, &A), "MatCreate");
  petsc_check(MatSetType(A, MATAIJ), "MatSetType");
  petsc_check(MatSetSizes(A, kModes * count, kModes * count, PETSC_DETERMINE, PETSC_DETERMINE),
              "MatSetSizes");
  petsc_check(MatSetBlockSize(A, kModes), "MatSetBlockSize");
  petsc_check(MatXAIJSetPreallocation(A, kModes, diagonal.data(), off.data(), nullptr, nullptr),
              "MatXAIJSetPreallocation");
  return A;
}

using PBlock = Eigen::Map<const Eigen::Matrix<double, 3, kModes, Eigen::RowMajor>>;
using CoarseBlock = Eigen::Matrix<double, kModes, kModes, Eigen::RowMajor>;

/// One block row of A_c being summed: its column blocks and their 6 x 6 blocks.
struct CoarseRow {
  std::vector<PetscInt> columns;
  std::vector<CoarseBlock, Eigen::aligned_allocator<CoarseBlock>> blocks;
  CoarseBlock& at(PetscInt column) {
    const auto k = std::find(columns.begin(), columns.end(), column) - columns.begin();
    if (k == static_cast<std::ptrdiff_t>(columns.size())) {
      columns.push_back(column);
      blocks.push_back(CoarseBlock::Zero());
    }
    return blocks[static_cast<std::size_t>(k)];
  }
  /// Into A at block row `row` (added), then empty.
  void add_to(Mat A, PetscInt row, std::vector<double>& packed) {
    const std::size_t n = columns.size();
    packed.resize(n * kModes * kModes);  // (6 rows of 6 n values, as MatSetValuesBlocked reads)
    for (std::size_t j = 0; j < n; ++j)
      for (int r = 0; r < kModes; ++r)
        for (int q = 0; q < kModes; ++q) packed[(r * n + j) * kModes + q] = blocks[j](r, q);
    petsc_check(MatSetValuesBlocked(A, 1, &row, static_cast<PetscInt>(n), columns.data(),
                                    packed.data(), ADD_VALUES),
                "MatSetValuesBlocked");
    columns.clear();
    blocks.clear();
  }
};

/// Node k's part of its aggregate's row of A_c: P_k^T K_kl P_l over its tetrahedra (rows k of
/// their element matrices) and P_k^T S_k P_k where it carries a spring block s (else null).
void add_node_row(const FirstLevel& c, const ElementStiffness& elements, const NodeGraph& tets,
                  std::int32_t k, const double* s, CoarseRow& row) {
  const PBlock pk(c.p.blocks.data() + 3 * kModes * k);
  for (std::int32_t q = 0; q < tets.degree(k); ++q) {
    const auto e = static_cast<std::size_t>(tets.of(k)[q]);
    const Tetrahedron& t = c.part->mesh.tets[e];
    const int a = static_cast<int>(std::find(t.begin(), t.end(), k) - t.begin());
    const Eigen::Matrix<double, 3, 12> K = elements.element_row(e, a);
    for (int l = 0; l < 4; ++l)
      if (c.base[t[l]] >= 0)
        row.at(c.base[t[l]] / kModes).noalias() +=
            pk.transpose() *
            (K.middleCols<3>(3 * l) * PBlock(c.p.blocks.data() + 3 * kModes * t[l]));
  }
  if (s)
    row.at(c.base[k] / kModes).noalias() +=
        pk.transpose() * Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(s) * pk;
}

/// A = P^T (K + S) P: each owned aggregate's block row summed here from its nodes' rows of this
/// rank's tetrahedra (one insertion per row), and each aggregated ghost's part of its owner's
/// row from the tetrahedra here (every tetrahedron is on one rank: the sum over the ranks is
/// P^T K P); P_k^T S_k P_k at the owned boundary nodes. Assembled, the dropped DOFs made
/// identity rows.
void add_galerkin_products(Mat A, const FirstLevel& c, const ElementStiffness& elements) {
  const MeshPartition& part = *c.part;
  const NodeGraph tets = node_tetrahedra(part.mesh);
  std::vector<const BoundaryNode*> spring(static_cast<std::size_t>(part.nodes()), nullptr);
  for (const BoundaryNode& node : c.fine->op->boundary())  // (each copy holds the whole block)
    if (part.owns(node.node, c.rank)) spring[node.node] = &node;
  const auto spring_of = [&spring](std::int32_t k, double* s) -> const double* {
    if (!spring[k]) return nullptr;
    boundary_block(*spring[k], {.stiffness = 1.0, .springs = true}, s);
    return s;
  };
  CoarseRow row;
  std::vector<double> packed;
  double s[9];
  const NodeGraph members = aggregate_members(c.aggregates);
  for (std::int32_t a = 0; a < c.aggregates.count; ++a) {
    for (std::int32_t m = 0; m < members.degree(a); ++m)
      add_node_row(c, elements, tets, members.of(a)[m], spring_of(members.of(a)[m], s), row);
    row.add_to(A, c.first + a, packed);
  }
  for (std::int32_t k = 0; k < part.shared; ++k)  // (a ghost's part of its owner's row)
    if (!part.owns(k, c.rank) && c.base[k] >= 0) {
      add_node_row(c, elements, tets, k, nullptr, row);
      row.add_to(A, c.base[k] / kModes, packed);
    }
  petsc_check(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
  petsc_check(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
  // an aggregate's dropped DOFs carry nothing: identity rows, so that A_c stays definite
  std::vector<PetscInt> dropped;
  for (std::size_t k = 0; k < c.p.dropped.size(); ++k)
    if (c.p.dropped[k]) dropped.push_back(kModes * c.first + static_cast<PetscInt>(k));
  petsc_check(MatZeroRowsColumns(A, static_cast<PetscInt>(dropped.size()), dropped.data(), 1.0,
                                 nullptr, nullptr),
              "MatZeroRowsColumns");
  petsc_check(MatSetOption(A, MAT_SPD, PETSC_TRUE), "MatSetOption");
}

/// The rigid-body modes' coarse vectors as A's near-null space.
void set_coarse_modes(Mat A, const FirstLevel& c) {
  const PetscInt count = c.aggregates.count;
  // GAMG's near-null space on A_c: the rigid-body modes' coarse vectors, orthonormalized
  Vec modes[kModes];
  for (int j = 0; j < kModes; ++j) {
    petsc_check(MatCreateVecs(A, &modes[j], nullptr), "MatCreateVecs");
    PetscScalar* v = nullptr;
    petsc_check(VecGetArray(modes[j], &v), "VecGetArray");
    for (PetscInt a = 0; a < count; ++a)
      for (int k = 0; k < kModes; ++k)
        v[kModes * a + k] = c.p.modes[kModes * kModes * a + kModes * j + k];
    petsc_check(VecRestoreArray(modes[j], &v), "VecRestoreArray");
    for (int i = 0; i < j; ++i) {
      PetscScalar along = 0.0;
      petsc_check(VecDot(modes[j], modes[i], &along), "VecDot");
      petsc_check(VecAXPY(modes[j], -along, modes[i]), "VecAXPY");
    }
    petsc_check(VecNormalize(modes[j], nullptr), "VecNormalize");
  }
  MatNullSpace space = nullptr;
  petsc_check(MatNullSpaceCreate(c.fine->comm, PETSC_FALSE, kModes, modes, &space),
              "MatNullSpaceCreate");
  petsc_check(MatSetNearNullSpace(A, space), "MatSetNearNullSpace");
  MatNullSpaceDestroy(&space);  // (the matrix holds it)
  for (Vec& v : modes) VecDestroy(&v);
}

}  // namespace

AggregationRankStatics::AggregationRankStatics(const MeshPartition& part, const SoilOperator& op,
                                               const ElementStiffness& elements, MPI_Comm comm,
                                               double tolerance)
    : part_(part), tolerance_(tolerance) {
  const auto start = std::chrono::steady_clock::now();
  petsc_ = std::make_unique<Petsc>(part, op, comm);
  Petsc& p = *petsc_;
  {
    const FirstLevel c = first_level(part, p.level);  // (its graph freed at the end)
    coarse_dofs_ = static_cast<long long>(kModes) * c.total;
    fine_dofs_ = 3LL * p.level.rows.total;
    p.interpolation = prolongator(c);
    p.coarse = preallocated_coarse(c);
    add_galerkin_products(p.coarse, c, elements);
    set_coarse_modes(p.coarse, c);
  }
  p.ksp =
      p.level.two_level_cg(p.coarse, p.interpolation, tolerance_, levels_, "aggregation multigrid");
  set_stop_test(petsc_->ksp, op, petsc_->level.stop);
  setup_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

AggregationRankStatics::~AggregationRankStatics() = default;

void AggregationRankStatics::set_stop_check(std::function<void()> check) {
  petsc_->level.stop.check = std::move(check);
}

std::string AggregationRankStatics::levels_detail() const {
  const double fewer =
      static_cast<double>(fine_dofs_) / static_cast<double>(std::max(1LL, coarse_dofs_));
  return " (the first coarse level " + std::to_string(coarse_dofs_) + " DOFs, 6 per aggregate, " +
         std::to_string(std::llround(fewer)) + " times fewer than the mesh's)";
}

Eigen::VectorXd AggregationRankStatics::solve(const Eigen::VectorXd& f) {
  Petsc& p = *petsc_;
  return solve_on_ranks(
      p.ksp, p.level.x, p.level.b, p.level.stop, part_, p.level.rows, p.level.fixed, f, iterations_,
      "the static solve on the ranks (PETSc's CG with the aggregation multigrid)");
}

}  // namespace rumble::fem
